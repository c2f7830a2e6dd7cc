#include "verify/exact_point.hpp"

#include "model/exact_coefficients.hpp"

#include <boost/multiprecision/gmp.hpp>
#include <mpfi.h>

#include <cmath>

namespace linkbox::verify {

namespace {

using Q = model::Rational;
using Vec = std::vector<Q>;
using Mat = std::vector<Vec>;

// Continued-fraction steps before the search gives up: a double interval a few ulps wide
// around a rational with a small denominator needs far fewer.
constexpr int kMaxSteps = 64;

std::optional<Q> simplest(const Q& lo, const Q& hi, int steps) {
  if (steps > kMaxSteps) return std::nullopt;
  if (lo <= 0 && hi >= 0) return Q(0);
  if (hi < 0) {
    auto s = simplest(-hi, -lo, steps);
    return s ? std::optional<Q>(-*s) : std::nullopt;
  }
  const Q whole(boost::multiprecision::mpz_int(numerator(lo) / denominator(lo)));  // floor for lo > 0
  if (whole == lo) return lo;
  if (whole + 1 <= hi) return whole + 1;
  auto s = simplest(1 / (hi - whole), 1 / (lo - whole), steps + 1);
  return s ? std::optional<Q>(whole + 1 / *s) : std::nullopt;
}

std::optional<Q> parse(const std::string& text) {
  try {
    if (text.empty() || text.size() > 4096) return std::nullopt;
    Q q(text);
    return q;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::optional<Q> eval(const model::Polynomial& p, const Vec& x) {
  Q sum = 0;
  for (auto& [powers, coefficient] : p.terms()) {
    auto c = model::exact_coefficient(p, powers, coefficient);
    if (!c) return std::nullopt;
    Q term = *c;
    for (auto [v, e] : powers) {
      if (v < 0 || static_cast<size_t>(v) >= x.size()) return std::nullopt;
      for (int k = 0; k < e; ++k) term *= x[v];
    }
    sum += term;
  }
  return sum;
}

// A basis of the null space of `a` (rows x cols), by reduction to row echelon form.
std::vector<Vec> null_space(Mat a, size_t cols) {
  std::vector<int> pivot_col;
  size_t row = 0;
  for (size_t c = 0; c < cols && row < a.size(); ++c) {
    size_t p = row;
    while (p < a.size() && a[p][c] == 0) ++p;
    if (p == a.size()) continue;
    std::swap(a[p], a[row]);
    for (size_t k = c + 1; k < cols; ++k) a[row][k] /= a[row][c];
    a[row][c] = 1;
    for (size_t r = 0; r < a.size(); ++r) {
      if (r == row || a[r][c] == 0) continue;
      const Q f = a[r][c];
      for (size_t k = c; k < cols; ++k) a[r][k] -= f * a[row][k];
    }
    pivot_col.push_back(static_cast<int>(c));
    ++row;
  }
  std::vector<Vec> basis;
  std::vector<bool> is_pivot(cols, false);
  for (int c : pivot_col) is_pivot[c] = true;
  for (size_t free = 0; free < cols; ++free) {
    if (is_pivot[free]) continue;
    Vec v(cols, Q(0));
    v[free] = 1;
    for (size_t r = 0; r < pivot_col.size(); ++r) v[pivot_col[r]] = -a[r][free];
    basis.push_back(std::move(v));
  }
  return basis;
}

std::optional<Vec> parse_all(const std::vector<std::string>& point) {
  Vec x;
  for (auto& s : point) {
    auto q = parse(s);
    if (!q) return std::nullopt;
    x.push_back(*q);
  }
  return x;
}

bool zero_at(const std::vector<model::Polynomial>& f, const Vec& x) {
  for (auto& e : f) {
    auto value = eval(e, x);
    if (!value || *value != 0) return false;
  }
  return !f.empty();
}

// An MPFI interval at `bits` of precision, cleared on exit.
struct Mpfi {
  mpfi_t v;
  explicit Mpfi(mpfr_prec_t bits) { mpfi_init2(v, bits); }
  ~Mpfi() { mpfi_clear(v); }
  Mpfi(const Mpfi&) = delete;
  Mpfi& operator=(const Mpfi&) = delete;
};

// Whether the angle of (c, s) (c^2 + s^2 = 1), as theta + 2 k pi for some k, lies in [lo, hi]:
// decided at `bits` of precision, or none.
std::optional<model::Side> angle_side(const Q& c, const Q& s, double lo, double hi, mpfr_prec_t bits) {
  Mpfi qc(bits), qs(bits), theta(bits), turn(bits), t(bits);
  mpfi_set_q(qc.v, c.backend().data());
  mpfi_set_q(qs.v, s.backend().data());
  mpfi_atan2(theta.v, qs.v, qc.v);  // in [-pi, pi]
  mpfi_const_pi(turn.v);
  mpfi_mul_ui(turn.v, turn.v, 2);
  // Every k with [2 k pi - pi, 2 k pi + pi] meeting [lo, hi], and one more each way.
  const long first = std::lround(std::floor(lo / 6.2831853)) - 2, last = std::lround(std::ceil(hi / 6.2831853)) + 2;
  bool undecided = false;
  for (long k = first; k <= last; ++k) {
    mpfi_mul_si(t.v, turn.v, k);
    mpfi_add(t.v, t.v, theta.v);
    if (mpfi_nan_p(t.v)) return std::nullopt;
    mpfr_t l, r;
    mpfr_inits2(bits, l, r, static_cast<mpfr_ptr>(nullptr));
    mpfi_get_left(l, t.v);
    mpfi_get_right(r, t.v);
    const bool inside = mpfr_cmp_d(l, lo) >= 0 && mpfr_cmp_d(r, hi) <= 0;
    const bool apart = mpfr_cmp_d(r, lo) < 0 || mpfr_cmp_d(l, hi) > 0;
    mpfr_clears(l, r, static_cast<mpfr_ptr>(nullptr));
    if (inside) return model::Side::inside;
    undecided = undecided || !apart;
  }
  if (undecided) return std::nullopt;
  return model::Side::outside;
}

model::Side exact_arc_side(const model::Inequality::Arc& a, const Vec& x) {
  if (a.c < 0 || a.s < 0 || static_cast<size_t>(std::max(a.c, a.s)) >= x.size()) return model::Side::boundary;
  const Q &c = x[a.c], &s = x[a.s];
  const double lo = a.domain.lower(), hi = a.domain.upper();
  // Far from 0 the turns to try are many and their count overflows: left undecided.
  if (c * c + s * s != 1 || !(std::fabs(lo) < 1e6 && std::fabs(hi) < 1e6)) return model::Side::boundary;
  for (mpfr_prec_t bits : {256, 4096})
    if (auto side = angle_side(c, s, lo, hi, bits)) return *side;
  return model::Side::boundary;
}

}  // namespace

const char* to_string(SingularKind k) {
  switch (k) {
    case SingularKind::crossing: return "crossing";
    case SingularKind::isolated: return "isolated";
    case SingularKind::degenerate: return "degenerate";
  }
  return "?";
}

std::optional<std::string> simplest_rational(double lo, double hi) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi) return std::nullopt;
  auto q = simplest(Q(lo), Q(hi), 0);
  if (!q) return std::nullopt;
  return q->str();
}

bool rational_in(const std::string& text, const Interval& x) {
  auto q = parse(text);
  return q && std::isfinite(x.lower()) && std::isfinite(x.upper()) && Q(x.lower()) <= *q && *q <= Q(x.upper());
}

std::optional<SingularKind> exact_singular_kind(const std::vector<model::Polynomial>& h,
                                                const std::vector<std::string>& point) {
  const size_t n = point.size();
  if (n < 2 || h.size() + 1 != n) return std::nullopt;
  Vec x;
  for (auto& s : point) {
    auto q = parse(s);
    if (!q) return std::nullopt;
    x.push_back(*q);
  }
  Mat jac(n - 1, Vec(n)), jac_t(n, Vec(n - 1));
  for (size_t i = 0; i + 1 < n; ++i) {
    auto value = eval(h[i], x);
    if (!value || *value != 0) return std::nullopt;
    for (size_t j = 0; j < n; ++j) {
      auto d = eval(h[i].derivative(static_cast<int>(j)), x);
      if (!d) return std::nullopt;
      jac[i][j] = jac_t[j][i] = *d;
    }
  }
  const auto kernel = null_space(jac, n);      // rank n - 2: a 2-dimensional kernel
  const auto left = null_space(jac_t, n - 1);  // and a 1-dimensional left kernel
  if (kernel.size() != 2 || left.size() != 1) return std::nullopt;
  Q form[2][2] = {{0, 0}, {0, 0}};
  for (size_t i = 0; i + 1 < n; ++i) {
    if (left[0][i] == 0) continue;
    for (size_t j = 0; j < n; ++j)
      for (size_t k = 0; k < n; ++k) {
        auto d = eval(h[i].derivative(static_cast<int>(j)).derivative(static_cast<int>(k)), x);
        if (!d) return std::nullopt;
        if (*d == 0) continue;
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b) form[a][b] += left[0][i] * *d * kernel[a][j] * kernel[b][k];
      }
  }
  const Q det = form[0][0] * form[1][1] - form[0][1] * form[1][0];
  return det < 0 ? SingularKind::crossing : det > 0 ? SingularKind::isolated : SingularKind::degenerate;
}

std::optional<std::vector<std::string>> exact_zero_in(const std::vector<model::Polynomial>& f, const Box& box) {
  std::vector<std::string> point;
  for (auto& side : box) {
    auto q = simplest_rational(side.lower(), side.upper());
    if (!q) return std::nullopt;
    point.push_back(*q);
  }
  if (!exact_zero(f, point)) return std::nullopt;
  return point;
}

bool known_coefficients(const std::vector<model::Polynomial>& f) {
  for (auto& p : f)
    for (auto& [powers, c] : p.terms())
      if (!model::exact_coefficient(p, powers, c)) return false;
  return true;
}

bool exact_zero(const std::vector<model::Polynomial>& f, const std::vector<std::string>& point) {
  const auto x = parse_all(point);
  return x && zero_at(f, *x);
}

bool rationals_in(const std::vector<std::string>& point, const Box& box) {
  if (point.size() != box.size()) return false;
  for (size_t i = 0; i < box.size(); ++i)
    if (!rational_in(point[i], box[i])) return false;
  return true;
}

bool exact_root_in(const std::vector<model::Polynomial>& f, const std::vector<std::string>& point, const Box& box) {
  return rationals_in(point, box) && exact_zero(f, point);
}

model::Side exact_side(const model::Inequality& c, const std::vector<std::string>& point) {
  const auto x = parse_all(point);
  if (!x) return model::Side::boundary;
  if (c.arc && !c.strict) return exact_arc_side(*c.arc, *x);
  const auto g = eval(c.g, *x);
  if (!g) return model::Side::boundary;
  return (c.strict ? *g < 0 : *g <= 0) ? model::Side::inside : model::Side::outside;
}

model::Side side_of_root(const model::Inequality& c, const Box& box, const std::vector<std::string>& exact) {
  const model::Side side = model::side_of(c, box);
  return side == model::Side::boundary && !exact.empty() ? exact_side(c, exact) : side;
}

}  // namespace linkbox::verify
