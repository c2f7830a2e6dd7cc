#include "newton/regular_inverse.hpp"

#include <Eigen/LU>

#include <cmath>

namespace linkbox::newton {

namespace {

// 2^-e with e the exponent of the largest |entry| of the vector (1 for a zero vector).
double power_of_two_scale(double largest) {
  if (!(largest > 0) || !std::isfinite(largest)) return 1.0;
  int e = 0;
  std::frexp(largest, &e);  // largest = m 2^e, m in [0.5, 1)
  return std::ldexp(1.0, 1 - e);
}

struct Scaled {
  Eigen::VectorXd rows, cols;
  Eigen::MatrixXd matrix;
};

Scaled equilibrate(const Eigen::MatrixXd& j) {
  Scaled s{Eigen::VectorXd(j.rows()), Eigen::VectorXd(j.cols()), j};
  for (int i = 0; i < j.rows(); ++i) {
    s.rows(i) = power_of_two_scale(s.matrix.row(i).cwiseAbs().maxCoeff());
    s.matrix.row(i) *= s.rows(i);
  }
  for (int k = 0; k < j.cols(); ++k) {
    s.cols(k) = power_of_two_scale(s.matrix.col(k).cwiseAbs().maxCoeff());
    s.matrix.col(k) *= s.cols(k);
  }
  return s;
}

// The LU of `j` when its rcond reaches `min_rcond`, of its equilibrated form otherwise.
struct Factored {
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  std::optional<Scaled> scaled;
};

std::optional<Factored> factor(const Eigen::MatrixXd& j, double min_rcond) {
  if (j.size() == 0 || j.rows() != j.cols() || !j.allFinite()) return std::nullopt;
  Factored f{Eigen::PartialPivLU<Eigen::MatrixXd>(j), std::nullopt};
  if (f.lu.rcond() >= min_rcond) return f;
  f.scaled = equilibrate(j);
  f.lu.compute(f.scaled->matrix);
  if (!(f.lu.rcond() >= min_rcond)) return std::nullopt;
  return f;
}

}  // namespace

std::optional<Eigen::MatrixXd> regular_inverse(const Eigen::MatrixXd& j, double min_rcond) {
  auto f = factor(j, min_rcond);
  if (!f) return std::nullopt;
  Eigen::MatrixXd c = f->lu.inverse();
  if (f->scaled) c = f->scaled->cols.asDiagonal() * c * f->scaled->rows.asDiagonal();
  if (!c.allFinite()) return std::nullopt;
  return c;
}

std::optional<Eigen::VectorXd> regular_solve(const Eigen::MatrixXd& j, const Eigen::VectorXd& b, double min_rcond) {
  auto f = factor(j, min_rcond);
  if (!f) return std::nullopt;
  if (!f->scaled) return Eigen::VectorXd(f->lu.solve(b));
  const Eigen::VectorXd y = f->lu.solve(f->scaled->rows.cwiseProduct(b));
  return Eigen::VectorXd(f->scaled->cols.cwiseProduct(y));
}

}  // namespace linkbox::newton
