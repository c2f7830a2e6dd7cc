#include "newton/interval_newton.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>

namespace linkbox::newton {

namespace {

bool usable(const SquareSystem& f, const Box& x, const Eigen::MatrixXd& c) {
  if (static_cast<int>(x.size()) != f.size() || c.rows() != f.size() || c.cols() != f.size())
    return false;
  if (!c.allFinite()) return false;
  for (auto& xi : x)
    if (!is_finite(xi) || xi.lower() > xi.upper()) return false;
  return true;
}

bool strictly_inside(const Interval& inner, const Interval& outer) {
  return is_finite(inner) && outer.lower() < inner.lower() && inner.upper() < outer.upper();
}

bool disjoint(const Interval& a, const Interval& b) {
  return a.upper() < b.lower() || b.upper() < a.lower();
}

// The centre y (a float point inside X) and the offsets X - y, enclosed.
struct Centred {
  Eigen::VectorXd y;
  IVector offset;
};

Centred centre(const Box& x) {
  Centred c{Eigen::VectorXd(x.size()), IVector(x.size())};
  for (size_t i = 0; i < x.size(); ++i) {
    c.y(i) = median(x[i]);
    c.offset(i) = x[i] - c.y(i);
  }
  return c;
}

}  // namespace

NewtonStep krawczyk_step(const SquareSystem& f, const Box& x, const Eigen::MatrixXd& c) {
  NewtonStep s;
  if (!usable(f, x, c)) {
    s.image = x;
    return s;
  }
  Centred yc = centre(x);
  // Offset form: K - y = -C F(y) + (I - C F'(X)) (X - y).
  IVector k = -multiply(c, f.values(point_box(yc.y))) + multiply(identity_minus(c, f.jacobian(x)), yc.offset);
  s.image.resize(x.size());
  s.interior = true;
  for (size_t i = 0; i < x.size(); ++i) {
    s.image[i] = yc.y(i) + k(i);
    s.interior = s.interior && strictly_inside(s.image[i], x[i]);
    s.excluded = s.excluded || disjoint(s.image[i], x[i]);
  }
  return s;
}

NewtonStep hansen_sengupta_step(const SquareSystem& f, const Box& x, const Eigen::MatrixXd& c) {
  NewtonStep s;
  s.image = x;
  if (!usable(f, x, c)) return s;
  Centred yc = centre(x);
  IMatrix a = multiply(c, f.jacobian(x));
  IVector b = -multiply(c, f.values(point_box(yc.y)));
  IVector& d = yc.offset;  // narrowed in place: later rows use the earlier rows' results
  s.interior = true;
  for (int i = 0; i < f.size(); ++i) {
    if (zero_in(a(i, i))) {  // no division: this row proves nothing
      s.interior = false;
      continue;
    }
    Interval sum = b(i);
    for (int j = 0; j < f.size(); ++j)
      if (j != i) sum -= a(i, j) * d(j);
    Interval n = sum / a(i, i);
    Interval moved = yc.y(i) + n;
    s.interior = s.interior && strictly_inside(moved, x[i]);
    Interval kept;
    if (!intersect(n, d(i), kept) || !intersect(moved, x[i], s.image[i])) {
      s.excluded = true;
      s.interior = false;
      return s;
    }
    d(i) = kept;
  }
  return s;
}

NewtonStep newton_step(Method m, const SquareSystem& f, const Box& x, const Eigen::MatrixXd& c) {
  return m == Method::krawczyk ? krawczyk_step(f, x, c) : hansen_sengupta_step(f, x, c);
}

bool at_most_one_root(const SquareSystem& f, const Box& y, const Eigen::MatrixXd& c) {
  if (!usable(f, y, c)) return false;
  return norm_inf_upper(identity_minus(c, f.jacobian(y))) < 1.0;
}

std::optional<Eigen::MatrixXd> combination_exclusion(const SquareSystem& f, const Box& x) {
  const int n = f.size();
  constexpr int kLargest = 64;  // the SVD is cubic in n
  if (n == 0 || n > kLargest) return std::nullopt;
  const Eigen::MatrixXd jm = midpoint(f.jacobian(x));
  const Eigen::VectorXd fy = midpoint(f.values(point_box(centre(x).y)));
  if (!jm.allFinite() || !fy.allFinite()) return std::nullopt;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(jm, Eigen::ComputeFullU);
  const double w = std::max(width_up(x[0]), std::numeric_limits<double>::min());
  for (int k = n - 1; k >= std::max(0, n - 2); --k) {  // the two smallest singular values
    const Eigen::VectorXd u = svd.matrixU().col(k);
    const double g = u.dot(fy);
    if (!(std::fabs(g) > 0)) continue;
    Eigen::MatrixXd c = Eigen::MatrixXd::Zero(n, n);
    c.row(0) = std::ldexp(w / g, 30) * u.transpose();
    if (c.allFinite() && krawczyk_step(f, x, c).excluded) return c;
  }
  return std::nullopt;
}

}  // namespace linkbox::newton
