#include "newton/arc.hpp"

#include "newton/float_system.hpp"
#include "newton/interval_newton.hpp"
#include "newton/regular_inverse.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

namespace linkbox::newton {

namespace {

std::vector<int> all_but(int n, int p) {
  std::vector<int> v;
  for (int i = 0; i < n; ++i)
    if (i != p) v.push_back(i);
  return v;
}

bool finite(const Box& b) {
  return std::all_of(b.begin(), b.end(), [](const Interval& x) { return is_finite(x); });
}

// A point of the curve near the piece's centre and the curve's tangent there (float: they
// only choose the parameter and the preconditioner).
std::optional<std::pair<Eigen::VectorXd, Eigen::VectorXd>> curve_point(const FloatSystem& fs, const Box& piece) {
  const Eigen::VectorXd x = fs.solve_from(centre(piece));
  const Eigen::MatrixXd j = fs.jacobian(x);
  if (!x.allFinite() || !j.allFinite()) return std::nullopt;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(j, Eigen::ComputeFullV);
  return std::make_pair(x, Eigen::VectorXd(svd.matrixV().col(j.cols() - 1)));
}

// The float inverse of `j`, empty when it is singular or not finite. Any C keeps a Krawczyk
// test sound; this one only makes it succeed.
std::optional<Eigen::MatrixXd> inverse_of(const Eigen::MatrixXd& j) {
  return regular_inverse(j, NewtonOptions{}.singular_rcond);
}

// The parametric Krawczyk step over B = box (t its side p, Y the others), in mean-value form
// in t as well as in y: with (t^, y^) the midpoint,
//   K = y^ - C F(t^, y^) - C F_t(B) ([t] - t^) + (I - C F_y(B)) (Y - y^).
// For each t in [t], F(t, y^) lies in F(t^, y^) + F_t(B) (t - t^) (mean value theorem), so
// the Krawczyk image with t held fixed lies in K. Evaluating F over [t] instead widens the
// image by the cancellation among a polynomial's terms, which the Jacobian's width avoids.
NewtonStep parametric_krawczyk(const std::shared_ptr<const model::CompiledSystem>& f, const Box& box, int p,
                               const Eigen::MatrixXd& c) {
  const int n = static_cast<int>(box.size());
  std::vector<FastInterval> d(f->nonzeros());
  {
    RoundingGuard guard;
    f->jacobian(box, d.data());
  }
  IMatrix jy = IMatrix::Constant(n - 1, n - 1, Interval(0.0));
  IVector jt = IVector::Constant(n - 1, Interval(0.0));
  for (int e = 0; e < f->nonzeros(); ++e) {
    const int row = f->entry_row(e), col = f->entry_col(e);
    const Interval v(d[e].lower(), d[e].upper());
    if (col == p) jt(row) = v;
    else jy(row, col < p ? col : col - 1) = v;
  }
  Box base = box;
  base[p] = Interval(median(box[p]));
  const SquareSystem at_mid(f, all_but(n, p), base);
  const Box y = at_mid.restrict(box);
  Eigen::VectorXd centre_y(n - 1);
  IVector offset(n - 1);
  for (int i = 0; i < n - 1; ++i) {
    centre_y(i) = median(y[i]);
    offset(i) = y[i] - centre_y(i);
  }
  IVector rhs = at_mid.values(point_box(centre_y));
  const Interval dt = box[p] - base[p];
  for (int i = 0; i < n - 1; ++i) rhs(i) += jt(i) * dt;
  const IVector k = -multiply(c, rhs) + multiply(identity_minus(c, jy), offset);
  NewtonStep step;
  step.image.resize(n - 1);
  step.interior = true;
  for (int i = 0; i < n - 1; ++i) {
    step.image[i] = centre_y(i) + k(i);
    const Interval& yi = y[i];
    step.interior = step.interior && is_finite(step.image[i]) && yi.lower() < step.image[i].lower() &&
                    step.image[i].upper() < yi.upper();
    step.excluded = step.excluded || step.image[i].upper() < yi.lower() || yi.upper() < step.image[i].lower();
  }
  return step;
}

// Parameters in order of how fast the curve crosses the piece along them: |v_p| / width_p.
std::vector<int> parameter_order(const Eigen::VectorXd& v, const Box& piece) {
  std::vector<int> order(piece.size());
  std::iota(order.begin(), order.end(), 0);
  auto speed = [&](int p) {
    const double w = piece[p].upper() - piece[p].lower();
    return w > 0 ? std::fabs(v(p)) / w : 0.0;
  };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return speed(a) > speed(b); });
  return order;
}

// Y widened by `fraction` of each side plus a hair, inside the domain's sides.
Box widen_within(const Box& y, double fraction, const Box& domain_y) {
  Box w = y;
  for (size_t i = 0; i < w.size(); ++i) {
    const double r = fraction * (y[i].upper() - y[i].lower()) + 1e-12 * (1 + std::fabs(median(y[i])));
    w[i] = y[i] + Interval(-r, r);
    if (!domain_y.empty() && !intersect(w[i], domain_y[i], w[i])) w[i] = y[i];
  }
  return w;
}

constexpr int kEndSteps = 8;  // Krawczyk rounds that tighten an end's enclosure

Box end_on(const std::shared_ptr<const model::CompiledSystem>& f, const Box& box, int p, double t,
           const Eigen::MatrixXd& c) {
  Box base = box;
  base[p] = Interval(t);
  const SquareSystem s(f, all_but(static_cast<int>(box.size()), p), base);
  Box y = s.restrict(box);
  Eigen::MatrixXd ck = c;
  for (int k = 0; k < kEndSteps; ++k) {
    // After two rounds with the arc's C, the inverse midpoint Jacobian of the end's own
    // enclosure: it contracts quadratically (any C keeps the enclosure sound).
    if (k == 2)
      if (auto own = inverse_of(midpoint(s.jacobian(y)))) ck = std::move(*own);
    const NewtonStep step = krawczyk_step(s, y, ck);
    Box next = y;
    bool ok = finite(step.image);
    for (size_t i = 0; ok && i < y.size(); ++i) ok = intersect(y[i], step.image[i], next[i]);
    if (!ok) break;  // cannot happen on a certified box: the root is in both
    y = std::move(next);
  }
  return s.embed(y);
}

// The arc that the Krawczyk step `step` of s (over box, parameter p, C) proves, if it does.
Arc arc_of(const std::shared_ptr<const model::CompiledSystem>& f, const SquareSystem& s, const NewtonStep& step,
           const Box& box, int p, const Eigen::MatrixXd& c) {
  Arc a;
  a.parameter = p;
  a.box = box;
  a.preconditioner = c;
  if (!step.interior) return a;
  a.certified = true;
  a.image = s.embed(step.image);
  a.ends[0] = end_on(f, box, p, box[p].lower(), c);
  a.ends[1] = end_on(f, box, p, box[p].upper(), c);
  return a;
}

}  // namespace

Arc arc_from(const std::shared_ptr<const model::CompiledSystem>& f, const Box& box, int parameter,
             const Eigen::MatrixXd& preconditioner) {
  const int n = static_cast<int>(box.size());
  if (n < 2 || f->rows() != n - 1 || f->cols() != n || parameter < 0 || parameter >= n || !finite(box) ||
      preconditioner.rows() != n - 1 || preconditioner.cols() != n - 1 || !preconditioner.allFinite()) {
    Arc a;
    a.parameter = parameter;
    a.box = box;
    a.preconditioner = preconditioner;
    return a;
  }
  const SquareSystem s(f, all_but(n, parameter), box);
  return arc_of(f, s, parametric_krawczyk(f, box, parameter, preconditioner), box, parameter, preconditioner);
}

Arc arc_over(const std::shared_ptr<const model::CompiledSystem>& f, const Box& box, int parameter) {
  const int n = static_cast<int>(box.size());
  Arc none;
  none.parameter = parameter;
  none.box = box;
  if (n < 2 || f->rows() != n - 1 || f->cols() != n || parameter < 0 || parameter >= n || !finite(box)) return none;
  const SquareSystem s(f, all_but(n, parameter), box);
  const auto c = inverse_of(midpoint(s.jacobian(s.restrict(box))));
  return c ? arc_from(f, box, parameter, *c) : none;
}

bool arc_excluded(const std::shared_ptr<const model::CompiledSystem>& f, const Box& box) {
  const int n = static_cast<int>(box.size());
  if (n < 2 || f->rows() != n - 1 || f->cols() != n || !finite(box)) return false;
  for (int p = 0; p < n; ++p) {
    const SquareSystem s(f, all_but(n, p), box);
    const auto c = inverse_of(midpoint(s.jacobian(s.restrict(box))));
    if (c && parametric_krawczyk(f, box, p, *c).excluded) return true;
  }
  return false;
}

Arc certify_arc(const std::shared_ptr<const model::CompiledSystem>& f, const Box& piece, const Box& domain,
                const NewtonOptions& options) {
  Arc none;
  none.box = piece;
  const int n = static_cast<int>(piece.size());
  if (n < 2 || f->rows() != n - 1 || f->cols() != n || !finite(piece)) return none;
  const auto point = curve_point(FloatSystem(f), piece);
  if (!point) return none;
  const auto& [x, tangent] = *point;
  const std::vector<int> order = parameter_order(tangent, piece);
  for (int p : order) {
    Box base = piece;
    base[p] = Interval(median(piece[p]));
    const SquareSystem at_mid(f, all_but(n, p), base);
    Eigen::VectorXd y(n - 1);
    for (int i = 0, r = 0; i < n; ++i)
      if (i != p) y(r++) = x(i);
    // Newton at t = mid from the curve point, then C = the inverse Jacobian there.
    for (int it = 0; it < options.newton_steps; ++it) {
      const Eigen::PartialPivLU<Eigen::MatrixXd> lu(at_mid.jacobian_at(y));
      const Eigen::VectorXd dy = lu.solve(at_mid.values_at(y));
      if (!dy.allFinite()) break;
      y -= dy;
      if (dy.lpNorm<Eigen::Infinity>() <= 1e-15 * (1 + y.lpNorm<Eigen::Infinity>())) break;
    }
    const auto inverse = inverse_of(at_mid.jacobian_at(y));
    if (!inverse) continue;
    const Eigen::MatrixXd& c = *inverse;
    // The parameter's side overlaps the neighbouring pieces a little, so that an end never
    // lies on another piece's face (contracted boxes meet the curve at their corners).
    Box span = piece;
    const double overlap = std::ldexp(piece[p].upper() - piece[p].lower(), -10);
    span[p] = piece[p] + Interval(-overlap, overlap);
    if (!domain.empty() && !intersect(span[p], domain[p], span[p])) span[p] = piece[p];
    const SquareSystem over_t(f, all_but(n, p), span);
    Box domain_y;
    if (!domain.empty()) domain_y = over_t.restrict(domain);
    const Box piece_y = over_t.restrict(piece);
    Box yb = piece_y;
    for (int i = 0; i < n - 1; ++i) yb[i] = hull(yb[i], Interval(y(i)));
    const double limit = 16 * max_width(piece);
    for (int round = 0; round < options.inflation_steps; ++round) {
      const Box trial = widen_within(yb, options.inflation, domain_y);
      if (max_width(trial) > limit) break;
      const NewtonStep step = parametric_krawczyk(f, over_t.embed(trial), p, c);
      if (step.interior) {
        Arc a = arc_of(f, over_t, step, over_t.embed(trial), p, c);
        if (contains(a.box, piece)) return a;
        break;
      }
      if (!finite(step.image)) break;
      // Rump's inflation from the image, never losing the piece: the arc's box must cover it.
      for (int i = 0; i < n - 1; ++i) yb[i] = hull(step.image[i], piece_y[i]);
    }
  }
  return none;
}

}  // namespace linkbox::newton
