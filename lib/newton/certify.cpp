#include "newton/certify.hpp"

#include "newton/regular_inverse.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

namespace linkbox::newton {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

bool finite_box(const Box& b) {
  return std::all_of(b.begin(), b.end(), [](const Interval& x) { return is_finite(x); });
}

Eigen::VectorXd centre_of(const Box& b) {
  Eigen::VectorXd c(b.size());
  for (size_t i = 0; i < b.size(); ++i) c(i) = median(b[i]);
  return c;
}

std::vector<double> to_std(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

// The caller's tolerance around the domain (not part of any proof).
Box widen(const Box& b, double slack) {
  Box w = b;
  for (auto& x : w) {
    double r = slack * (1 + (x.upper() - x.lower()));
    x = x + Interval(-r, r);
  }
  return w;
}

// The float root must stay near the hull: farther away it is some other cluster's root.
bool near_hull(const Box& hull, const Eigen::VectorXd& x, double margin) {
  double m = margin * max_width(hull);
  for (size_t i = 0; i < hull.size(); ++i) {
    double tol = m + 1e-9 * (1 + std::fabs(x(i)));
    if (!(x(i) >= hull[i].lower() - tol && x(i) <= hull[i].upper() + tol)) return false;
  }
  return true;
}

// Proves that the interval matrix `j` holds a singular matrix, so that no Newton test can
// succeed on its box: with M the midpoint and v a float null vector of M (its last right
// singular vector), S = M - (M v) v^T / (v^T v) has S v = 0 exactly, and S lies in `j` when the
// outward enclosure of each of its entries does. Sufficient, not necessary (false: not shown).
bool holds_singular_matrix(const IMatrix& j) {
  const Eigen::MatrixXd m = midpoint(j);
  if (m.size() == 0 || m.rows() != m.cols() || !m.allFinite()) return false;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeFullV);
  const Eigen::VectorXd v = svd.matrixV().col(m.cols() - 1);
  Interval vv(0.0);
  for (int k = 0; k < v.size(); ++k) vv += Interval(v(k)) * Interval(v(k));
  if (!(vv.lower() > 0)) return false;
  for (int i = 0; i < m.rows(); ++i) {
    Interval r(0.0);  // (M v)_i
    for (int k = 0; k < m.cols(); ++k) r += Interval(m(i, k)) * Interval(v(k));
    for (int k = 0; k < m.cols(); ++k)
      if (!boost::numeric::subset(Interval(m(i, k)) - r * Interval(v(k)) / vv, j(i, k))) return false;
  }
  return true;
}

struct FloatRoot {
  Eigen::VectorXd x;
  bool finite = true;
  bool singular = false;
};

// Plain Newton in double. Only finds the start for inflation; proves nothing.
FloatRoot float_newton(const SquareSystem& s, Eigen::VectorXd x, const NewtonOptions& o) {
  double last_step = kInf;
  for (int k = 0; k < o.newton_steps; ++k) {
    Eigen::VectorXd fx = s.values_at(x);
    Eigen::MatrixXd j = s.jacobian_at(x);
    if (!fx.allFinite() || !j.allFinite()) return {x, false, false};
    if (fx.isZero(0)) break;
    const auto solved = regular_solve(j, fx, o.singular_rcond);
    if (!solved) return {x, true, true};
    const Eigen::VectorXd& dx = *solved;
    if (!dx.allFinite()) return {x, false, false};
    x -= dx;
    const double step = dx.lpNorm<Eigen::Infinity>(), size = x.lpNorm<Eigen::Infinity>();
    if (step <= 4 * kEps * size) break;
    // At the rounding noise of F the steps stop shrinking quadratically: further ones only
    // move x around the root.
    if (step <= 1e-9 * (1 + size) && step > 0.25 * last_step) break;
    last_step = step;
  }
  return {x, x.allFinite(), false};
}

// Rump's epsilon-inflation: X grows from the float root until its Newton image falls inside.
// The absolute terms let a box around an exactly representable root (F(x) = 0) reach a
// width the test can resolve, and zero components leave zero. They scale with the root's
// largest coordinate: F(y)'s rounding error, which the image's width must exceed, is relative
// to the terms of F, not to a zero coordinate (see papers/decisions/model-and-verify.md).
std::optional<std::pair<Box, NewtonStep>> inflate(const SquareSystem& s, const Eigen::VectorXd& root,
                                                  const Eigen::MatrixXd& c, const NewtonOptions& o,
                                                  Box& last, NewtonStep& last_step) {
  const double scale = root.lpNorm<Eigen::Infinity>();
  Box x = point_box(root);
  for (int k = 0; k < o.inflation_steps; ++k) {
    for (size_t i = 0; i < x.size(); ++i) {
      double eta = std::ldexp(std::fabs(root(i)), -48) + std::ldexp(scale, -50) +
                   std::numeric_limits<double>::min();
      double r = o.inflation * (x[i].upper() - x[i].lower()) + eta;
      x[i] = x[i] + Interval(-r, r);
    }
    NewtonStep step = newton_step(o.method, s, x, c);
    last = x, last_step = step;
    if (step.interior) return std::make_pair(x, step);
    if (!finite_box(step.image)) break;
    x = step.image;
  }
  return std::nullopt;
}

// No other root of F in hull(hull, x): x holds the only one, and F is injective on the
// union's hull when ||I - C F'|| < 1 there, with the certificate's C or one fitted to it.
bool unique_over(const SquareSystem& s, const Box& hull, const Box& x, const Eigen::MatrixXd& c,
                 const NewtonOptions& o) {
  if (contains(x, hull)) return true;
  Box y = linkbox::hull(hull, x);
  if (at_most_one_root(s, y, c)) return true;
  auto cy = regular_inverse(midpoint(s.jacobian(y)), o.singular_rcond);
  return cy && at_most_one_root(s, y, *cy);
}

// Nudged starting points after the centre: a Jacobian singular exactly at the centre
// (symmetric problems) should not end the attempt.
std::vector<Eigen::VectorXd> starts(const Box& hull) {
  Eigen::VectorXd c = centre_of(hull), d(hull.size());
  for (size_t i = 0; i < hull.size(); ++i)
    d(i) = (hull[i].upper() - hull[i].lower()) * 0.0617 * (i % 2 ? -1.0 : 1.0) * (1 + 0.1 * i);
  return {c, c + d, c - 2 * d};
}

// One tightening round; returns true when nothing smaller passed (done).
bool tighten(const SquareSystem& s, const NewtonOptions& o, const Eigen::MatrixXd& c, Box& x,
             NewtonStep& step) {
  const size_t n = x.size();
  for (int j = 0; j < 64; ++j) {
    Box next(n);
    bool smaller = false;
    for (size_t i = 0; i < n; ++i) {
      const Interval& k = step.image[i];
      double pad = 0;
      if (j > 0) {
        double eta = std::ldexp(std::max(std::fabs(k.lower()), std::fabs(k.upper())), -50) +
                     std::numeric_limits<double>::min();
        pad = std::ldexp((k.upper() - k.lower()) + eta, 2 * (j - 1));
      }
      if (!intersect(k + Interval(-pad, pad), x[i], next[i])) next[i] = x[i];  // not when interior
      smaller = smaller || next[i].lower() != x[i].lower() || next[i].upper() != x[i].upper();
    }
    if (!smaller) return true;  // grown back to X
    NewtonStep ns = newton_step(o.method, s, next, c);
    if (ns.interior) {
      x = std::move(next), step = std::move(ns);
      return false;
    }
  }
  return true;
}

Certificate fail(Certificate c, Reason r) {
  c.status = Status::unverified;
  c.reason = r;
  return c;
}

// A box that passes the Newton test with preconditioner c, and that step (its image).
struct Passing {
  Box x;
  NewtonStep step;
  Eigen::MatrixXd c;
};

// 1. The hull itself: may prove it root-free (that failure is returned), or certify it whole
// (`passing` is set).
std::optional<Certificate> test_hull(const SquareSystem& s, const Box& hull, const NewtonOptions& o,
                                     Certificate cert, std::optional<Passing>& passing) {
  cert.point = to_std(centre_of(hull));
  if (auto ch = regular_inverse(midpoint(s.jacobian(hull)), o.singular_rcond)) {
    NewtonStep hs = newton_step(o.method, s, hull, *ch);
    if (hs.excluded) {
      cert.image = hs.image, cert.preconditioner = *ch;
      return fail(cert, Reason::no_root);
    }
    if (hs.interior) {
      passing = Passing{hull, hs, *ch};
      return std::nullopt;
    }
  }
  if (auto c = combination_exclusion(s, hull)) {
    cert.method = Method::krawczyk;
    cert.image = krawczyk_step(s, hull, *c).image, cert.preconditioner = *c;
    return fail(cert, Reason::no_root);
  }
  return std::nullopt;
}

// 2. Float Newton from the centre (or nudged starts if that fails), then inflation. Returns
// the failure, or sets `passing` and the certificate's point, box and preconditioner.
std::optional<Certificate> inflate_float_root(const SquareSystem& s, const Box& hull, const NewtonOptions& o,
                                              Certificate& cert, std::optional<Passing>& passing) {
  std::optional<Certificate> first_failure;
  Eigen::VectorXd root;
  for (const Eigen::VectorXd& start : starts(hull)) {
    FloatRoot fr = float_newton(s, start, o);
    Certificate attempt = cert;
    attempt.point = to_std(fr.x);
    attempt.box = point_box(fr.x);
    Reason r = !fr.finite ? Reason::non_finite
               : fr.singular ? Reason::singular_jacobian
               : !near_hull(hull, fr.x, o.hull_margin) ? Reason::outside_hull
               : Reason::none;
    if (r == Reason::none) {
      cert = attempt, root = fr.x;
      break;
    }
    if (!first_failure) first_failure = fail(attempt, r);
  }
  if (root.size() == 0) {
    if (first_failure->reason == Reason::singular_jacobian && holds_singular_matrix(s.jacobian(hull)))
      first_failure->reason = Reason::singular_in_box;
    return *first_failure;
  }
  auto ci = regular_inverse(s.jacobian_at(root), o.singular_rcond);
  if (!ci) return fail(cert, holds_singular_matrix(s.jacobian(hull)) ? Reason::singular_in_box : Reason::singular_jacobian);
  const Eigen::MatrixXd c = *ci;
  cert.preconditioner = c;
  NewtonStep step;
  auto done = inflate(s, root, c, o, cert.box, step);
  if (!done) {
    cert.image = step.image;
    return fail(cert, holds_singular_matrix(s.jacobian(hull)) ? Reason::singular_in_box : Reason::inflation_failed);
  }
  passing = Passing{done->first, done->second, c};
  return std::nullopt;
}

// 4. Where that root lies: in the hull, and in the domain or within its slack.
Certificate locate_root(const SquareSystem& s, const Box& hull, const Box& domain, const NewtonOptions& o,
                        Certificate cert, Passing p, bool unique_in_hull) {
  const size_t n = static_cast<size_t>(s.size());
  if (!overlaps(p.step.image, hull)) return fail(cert, Reason::outside_hull);
  if (domain.empty()) {
    cert.root_in_domain = true;
  } else {
    if (!overlaps(p.step.image, domain)) return fail(cert, Reason::outside_domain);
    if (!contains(domain, p.x)) {
      // The part of X inside the domain may pass on its own (root near, not on, the face).
      Box inner(n);
      bool meets = true;
      for (size_t i = 0; i < n; ++i) meets = meets && intersect(p.x[i], domain[i], inner[i]);
      NewtonStep ns;
      if (meets && (ns = newton_step(o.method, s, inner, p.c)).interior) {
        p.x = std::move(inner), p.step = std::move(ns);
        cert.box = p.x, cert.image = p.step.image, cert.point = to_std(centre_of(p.step.image));
      }
    }
    cert.root_in_domain = contains(domain, p.step.image);
    cert.on_domain_boundary = !contains(domain, p.x);
    if (cert.on_domain_boundary && !(o.domain_slack > 0 && contains(widen(domain, o.domain_slack), p.x)))
      return fail(cert, Reason::outside_domain);
  }
  cert.unique_in_hull = unique_in_hull || unique_over(s, hull, p.x, p.c, o);
  cert.status = Status::certified;
  cert.reason = Reason::none;
  return cert;
}

// The whole pipeline in the unknowns' coordinates.
Certificate certify_square(const SquareSystem& s, const Box& hull, const Box& domain,
                           const NewtonOptions& o) {
  Certificate cert;
  cert.method = o.method;
  const size_t n = static_cast<size_t>(s.size());
  cert.box = hull;
  if (n == 0 || hull.size() != n || (!domain.empty() && domain.size() != n))
    return fail(cert, Reason::not_square);
  if (!finite_box(hull)) return fail(cert, Reason::non_finite);

  std::optional<Passing> passing;
  if (auto no_root = test_hull(s, hull, o, cert, passing)) return *no_root;
  const bool unique_in_hull = passing.has_value();
  if (!passing)
    if (auto failure = inflate_float_root(s, hull, o, cert, passing)) return *failure;
  Passing& p = *passing;

  // 3. Tighten: every X <- K(X) ∩ X still holds the root; keep the last X that passes.
  // The image is often far tighter than what can pass in turn (it sits at the rounding
  // limit), so candidates grow from it by factors of 4 until one passes. A round that
  // narrows X by less than a quarter is at that limit: later rounds move last digits only.
  for (int t = 0; t < o.tighten_steps; ++t) {
    const double before = max_width(p.x);
    if (tighten(s, o, p.c, p.x, p.step) || max_width(p.x) > 0.75 * before) break;
  }
  cert.box = p.x;
  cert.image = p.step.image;
  cert.preconditioner = p.c;
  cert.point = to_std(centre_of(p.step.image));

  return locate_root(s, hull, domain, o, std::move(cert), std::move(p), unique_in_hull);
}

std::optional<SquareSystem> square_system(const std::vector<model::Polynomial>& f, std::vector<int> unknowns,
                                          const Box& base) {
  try {
    return SquareSystem(f, std::move(unknowns), base);
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

std::vector<int> all_but(size_t n, int skip) {
  std::vector<int> v;
  for (int i = 0; i < static_cast<int>(n); ++i)
    if (i != skip) v.push_back(i);
  return v;
}

// Parameters ordered by the reciprocal condition number (SVD) of the remaining square
// Jacobian at the box centre, best first.
std::vector<int> parameters_by_conditioning(const model::CompiledSystem& f, const Box& box) {
  const int n = static_cast<int>(box.size());
  std::vector<FastInterval> d(f.nonzeros());
  {
    RoundingGuard guard;
    f.jacobian(point_box(centre_of(box)), d.data());
  }
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(n - 1, n);
  for (int e = 0; e < f.nonzeros(); ++e) j(f.entry_row(e), f.entry_col(e)) = median(as_protected(d[e]));
  std::vector<std::pair<double, int>> ranked;
  for (int p = 0; p < n; ++p) {
    Eigen::MatrixXd sub(n - 1, n - 1);
    for (int k = 0, col = 0; k < n; ++k)
      if (k != p) sub.col(col++) = j.col(k);
    double quality = 0;
    if (sub.allFinite()) {
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(sub);
      auto sv = svd.singularValues();
      if (sv.size() > 0 && sv(0) > 0) quality = sv(sv.size() - 1) / sv(0);
    }
    ranked.emplace_back(-quality, p);
  }
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](auto& a, auto& b) { return a.first < b.first; });
  std::vector<int> order;
  for (auto& r : ranked) order.push_back(r.second);
  return order;
}

Certificate crossing_for(const std::shared_ptr<const model::CompiledSystem>& f, const Box& box, int p,
                         const NewtonOptions& o) {
  Box base = box;
  const double value = median(box[p]);
  base[p] = Interval(value);
  const SquareSystem s(f, all_but(box.size(), p), base);
  Box sub = s.restrict(box);
  Certificate c = certify_square(s, sub, sub, o);
  if (c.box.size() == sub.size()) c.box = s.embed(c.box);
  if (c.image.size() == sub.size()) c.image = s.embed(c.image);
  if (c.point.size() == sub.size()) c.point.insert(c.point.begin() + p, value);
  c.fixed_variable = p;
  return c;
}

}  // namespace

const char* to_string(Reason r) {
  switch (r) {
    case Reason::none: return "none";
    case Reason::not_square: return "not square";
    case Reason::non_finite: return "non-finite";
    case Reason::singular_jacobian: return "singular Jacobian";
    case Reason::inflation_failed: return "inflation failed";
    case Reason::singular_in_box:
      return "singular Jacobian in the cluster (its interval Jacobian holds a singular matrix: a multiple root, a "
             "singular point, or a curve)";
    case Reason::outside_hull: return "root outside the hull";
    case Reason::outside_domain: return "root outside the domain";
    case Reason::no_root: return "no root (proved)";
  }
  return "?";
}

Certificate certify_root(const std::vector<model::Polynomial>& f, const Box& hull, const Box& domain,
                         const NewtonOptions& options) {
  auto s = square_system(f, all_but(hull.size(), -1), Box(hull.size(), Interval(0.0)));
  if (!s) {
    Certificate c;
    c.method = options.method;
    c.box = hull;
    return fail(c, Reason::not_square);
  }
  return certify_square(*s, hull, domain, options);
}

Certificate certify_root(const SquareSystem& f, const Box& hull, const Box& domain, const NewtonOptions& options) {
  return certify_square(f, hull, domain, options);
}

Certificate certify_curve_crossing(const std::vector<model::Polynomial>& f, const Box& box, int parameter,
                                   const NewtonOptions& options) {
  for (auto& e : f)
    for (int v : e.variables())
      if (v >= static_cast<int>(box.size())) {
        Certificate bad;
        bad.method = options.method;
        bad.box = box;
        bad.fixed_variable = parameter;
        return fail(bad, Reason::not_square);
      }
  return certify_curve_crossing(std::make_shared<const model::CompiledSystem>(f, box.size()), box, parameter, options);
}

Certificate certify_curve_crossing(const std::shared_ptr<const model::CompiledSystem>& f, const Box& box,
                                   int parameter, const NewtonOptions& options) {
  Certificate bad;
  bad.method = options.method;
  bad.box = box;
  bad.fixed_variable = parameter;
  const int n = static_cast<int>(box.size());
  if (n < 2 || f->rows() != n - 1 || f->cols() != n || parameter >= n) return fail(bad, Reason::not_square);
  if (!finite_box(box)) return fail(bad, Reason::non_finite);
  std::vector<int> order = parameter >= 0 ? std::vector<int>{parameter} : parameters_by_conditioning(*f, box);
  std::optional<Certificate> first;
  for (int p : order) {
    Certificate c = crossing_for(f, box, p, options);
    if (c.status == Status::certified) return c;
    if (!first) first = std::move(c);
  }
  return *first;
}

bool recheck_krawczyk(const std::vector<model::Polynomial>& f, const Box& box, const Eigen::MatrixXd& c) {
  auto s = square_system(f, all_but(box.size(), -1), box);
  return s && krawczyk_step(*s, box, c).interior;
}

bool recheck_hansen_sengupta(const std::vector<model::Polynomial>& f, const Box& box,
                             const Eigen::MatrixXd& c) {
  auto s = square_system(f, all_but(box.size(), -1), box);
  return s && hansen_sengupta_step(*s, box, c).interior;
}

bool recheck_curve_crossing(const std::vector<model::Polynomial>& f, const Box& box, int parameter,
                            const Eigen::MatrixXd& c, Method method) {
  // The certificate speaks of one hyperplane: the fixed side must be a single value.
  if (parameter < 0 || parameter >= static_cast<int>(box.size()) ||
      !(box[parameter].lower() == box[parameter].upper()))
    return false;
  auto s = square_system(f, all_but(box.size(), parameter), box);
  return s && newton_step(method, *s, s->restrict(box), c).interior;
}

bool recheck_exclusion(const std::vector<model::Polynomial>& f, const Box& box, const Eigen::MatrixXd& c,
                       Method method) {
  auto s = square_system(f, all_but(box.size(), -1), box);
  return s && newton_step(method, *s, box, c).excluded;
}

bool recheck(const std::vector<model::Polynomial>& f, const Certificate& cert) {
  if (cert.fixed_variable >= 0)
    return recheck_curve_crossing(f, cert.box, cert.fixed_variable, cert.preconditioner, cert.method);
  return cert.method == Method::krawczyk ? recheck_krawczyk(f, cert.box, cert.preconditioner)
                                         : recheck_hansen_sengupta(f, cert.box, cert.preconditioner);
}

}  // namespace linkbox::newton
