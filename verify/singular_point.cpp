#include "verify/singular_point.hpp"

#include "newton/interval_eigen.hpp"
#include "newton/square_system.hpp"

#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>

#include <cmath>

namespace linkbox::verify {

namespace {

using model::Polynomial;
using newton::IMatrix;
using newton::IVector;

// Halvings of U's reach tried before the certificate's own tight box.
constexpr int kReachSteps = 12;
// The float root's box handed to certify_root, relative: wide enough not to be a point.
constexpr double kHullRadius = 1e-12;

// G(u, e, mu) over the variables u (0..n-1), e (n..2n-2), mu (2n-1).
std::vector<Polynomial> augmented(const std::vector<Polynomial>& h, const std::vector<double>& l) {
  const int n = static_cast<int>(h.size()) + 1;
  const Polynomial mu = Polynomial::variable(2 * n - 1);
  std::vector<Polynomial> g;
  for (int i = 0; i + 1 < n; ++i) g.push_back(h[i] - mu * Polynomial::variable(n + i));
  for (int j = 0; j < n; ++j) {
    Polynomial s;
    for (int i = 0; i + 1 < n; ++i) s += Polynomial::variable(n + i) * h[i].derivative(j);
    g.push_back(s);
  }
  Polynomial norm = Polynomial::constant(Interval(-1.0));
  for (int i = 0; i + 1 < n; ++i) norm += Polynomial::variable(n + i) * Interval(l[i]);
  g.push_back(norm);
  return g;
}

Box part(const Box& b, size_t from, size_t count) { return Box(b.begin() + from, b.begin() + from + count); }

// Every e with H'(u)^T e = 0 and l . e = 1, for any u in U, lies in E: with C a float
// left inverse of the midpoint of M = (H'(U)^T; l^T) and beta >= ||I - C M||, beta < 1,
// every such e is within ||C (b - M e~)|| / (1 - beta) of e~ (max norm).
bool left_kernel_in(const std::vector<Polynomial>& h, const std::vector<double>& l, const Box& u, const Box& e) {
  const Eigen::Index n = static_cast<Eigen::Index>(u.size());
  IMatrix m(n + 1, n - 1);
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) m(j, i) = h[i].derivative(static_cast<int>(j)).eval(u);
    m(n, i) = Interval(l[i]);
  }
  const Eigen::MatrixXd mid = newton::midpoint(m);
  if (!mid.allFinite()) return false;
  const Eigen::MatrixXd c = mid.completeOrthogonalDecomposition().pseudoInverse();
  if (!c.allFinite()) return false;
  const double beta = newton::norm_inf_upper(newton::identity_minus(c, m));
  if (!(beta < 1)) return false;
  Eigen::VectorXd guess(n - 1);
  for (Eigen::Index i = 0; i + 1 < n; ++i) guess(i) = median(e[i]);
  IVector residual = -newton::multiply(m, newton::to_ivector(newton::point_box(guess)));
  residual(n) += Interval(1.0);
  const IVector d = newton::multiply(c, residual);
  double delta = 0;
  for (Eigen::Index i = 0; i < d.size(); ++i) delta = std::max({delta, -d(i).lower(), d(i).upper()});
  const double radius = (Interval(delta) / (Interval(1.0) - Interval(beta))).upper();
  if (!std::isfinite(radius)) return false;
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    const Interval ball = Interval(guess(i)) + Interval(-radius, radius);
    if (ball.lower() < e[i].lower() || ball.upper() > e[i].upper()) return false;
  }
  return true;
}

// The tests on one box: G's Krawczyk test, the left kernel's bound, mu = 0 and p in it.
bool holds(const std::vector<Polynomial>& h, const std::vector<Polynomial>& g, const SingularPoint& s) {
  const size_t n = h.size() + 1;
  if (s.box.size() != 2 * n || s.point.size() != n || !zero_in(s.box[2 * n - 1])) return false;
  for (size_t j = 0; j < n; ++j)
    if (!rational_in(s.point[j], s.box[j])) return false;
  return newton::recheck_krawczyk(g, s.box, s.preconditioner) &&
         left_kernel_in(h, s.normal, part(s.box, 0, n), part(s.box, n, n - 1));
}

// The float start: the piece's middle, e the left singular vector of the smallest singular
// value there (so l = e), mu = l . H.
Eigen::VectorXd start(const std::vector<Polynomial>& h, const Box& piece, std::vector<double>& l) {
  const Eigen::Index n = static_cast<Eigen::Index>(piece.size());
  Box mid = piece;
  for (auto& x : mid) x = Interval(median(x));
  Eigen::MatrixXd jac(n - 1, n);
  Eigen::VectorXd value(n - 1);
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    value(i) = median(h[i].eval(mid));
    for (Eigen::Index j = 0; j < n; ++j) jac(i, j) = median(h[i].derivative(static_cast<int>(j)).eval(mid));
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(jac, Eigen::ComputeFullU);
  const Eigen::VectorXd e = svd.matrixU().col(n - 2);
  l.assign(e.data(), e.data() + e.size());
  Eigen::VectorXd x(2 * n);
  for (Eigen::Index j = 0; j < n; ++j) x(j) = median(mid[j]);
  x.segment(n, n - 1) = e;
  x(2 * n - 1) = e.dot(value);
  return x;
}

// Newton's iteration on G in double arithmetic; none when it does not settle.
std::optional<Eigen::VectorXd> float_newton(const std::vector<Polynomial>& g, Eigen::VectorXd x, int steps) {
  const auto system = newton::SquareSystem::all_unknown(g, static_cast<size_t>(x.size()));
  for (int k = 0; k < steps; ++k) {
    const Eigen::VectorXd step = system.jacobian_at(x).partialPivLu().solve(system.values_at(x));
    if (!step.allFinite()) return std::nullopt;
    x -= step;
    if (step.lpNorm<Eigen::Infinity>() <= 1e-15 * (1 + x.lpNorm<Eigen::Infinity>())) return x;
  }
  return x.allFinite() ? std::optional<Eigen::VectorXd>(x) : std::nullopt;
}

}  // namespace

Box SingularPoint::where() const { return part(box, 0, normal.size() + 1); }

std::optional<SingularPoint> prove_singular_point(const std::vector<Polynomial>& h, std::uint64_t chart,
                                                  const Box& piece, double reach,
                                                  const newton::NewtonOptions& options) {
  const size_t n = h.size() + 1;
  if (n < 2 || piece.size() != n) return std::nullopt;
  SingularPoint s;
  s.chart = chart;
  const Eigen::VectorXd x = start(h, piece, s.normal);
  if (!x.allFinite()) return std::nullopt;
  const auto g = augmented(h, s.normal);
  const auto root = float_newton(g, x, options.newton_steps);
  if (!root) return std::nullopt;
  Box hull = newton::point_box(*root);
  for (auto& c : hull) c = c + Interval(-kHullRadius, kHullRadius) * (1 + std::abs(median(c)));
  const newton::Certificate cert = newton::certify_root(g, hull, {}, options);
  if (cert.status != newton::Status::certified || !zero_in(cert.box[2 * n - 1])) return std::nullopt;
  for (size_t j = 0; j < n; ++j) {
    auto q = simplest_rational(cert.box[j].lower(), cert.box[j].upper());
    if (!q) return std::nullopt;
    s.point.push_back(*q);
  }
  auto kind = exact_singular_kind(h, s.point);
  if (!kind) return std::nullopt;
  s.kind = *kind;
  s.preconditioner = cert.preconditioner;
  Box centre = cert.box;
  for (auto& c : centre) c = Interval(median(c));
  for (int step = 0; step <= kReachSteps; ++step) {
    const double r = std::ldexp(reach, -step);
    // E and M wider than U first: e and mu move about as fast as u near the point, and E
    // must hold e for every u in U.
    for (double k : {4.0, 1.0}) {
      s.box = centre;
      for (size_t j = 0; j < 2 * n; ++j) s.box[j] = s.box[j] + (j < n ? Interval(-r, r) : Interval(-k * r, k * r));
      if (holds(h, g, s)) return s;
    }
  }
  s.box = cert.box;
  if (holds(h, g, s)) return s;
  return std::nullopt;
}

bool reprove_singular_point(const std::vector<Polynomial>& h, SingularPoint& s) {
  const size_t n = h.size() + 1;
  if (n < 2 || s.normal.size() + 1 != n || s.box.size() != 2 * n ||
      s.preconditioner.rows() != static_cast<Eigen::Index>(2 * n) ||
      s.preconditioner.cols() != static_cast<Eigen::Index>(2 * n))
    return false;
  for (double v : s.normal)
    if (!std::isfinite(v)) return false;
  auto kind = exact_singular_kind(h, s.point);
  if (!kind || !holds(h, augmented(h, s.normal), s)) return false;
  s.kind = *kind;
  return true;
}

}  // namespace linkbox::verify
