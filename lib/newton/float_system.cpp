#include "newton/float_system.hpp"


#include <Eigen/QR>

#include <algorithm>

namespace linkbox::newton {

FloatSystem::FloatSystem(const std::vector<model::Polynomial>& f, size_t unknowns)
    : f_(std::make_shared<const model::CompiledSystem>(f, unknowns)) {}

// Compiled, in plain double: these run in loops over every member of a cluster, and
// Polynomial::eval's protected interval operations (a rounding-mode switch each) were most of
// the time of verifying a curve.
Eigen::VectorXd FloatSystem::values(const Eigen::VectorXd& x) const {
  Eigen::VectorXd r(f_->rows());
  f_->values_float(x.data(), r.data());
  return r;
}

Eigen::MatrixXd FloatSystem::jacobian(const Eigen::VectorXd& x) const {
  std::vector<double> d(f_->nonzeros());
  f_->jacobian_float(x.data(), d.data());
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(f_->rows(), x.size());
  for (int e = 0; e < f_->nonzeros(); ++e) j(f_->entry_row(e), f_->entry_col(e)) = d[e];
  return j;
}

Eigen::VectorXd FloatSystem::solve_from(Eigen::VectorXd x) const {
  for (int it = 0; it < 30; ++it) {
    const Eigen::VectorXd dx = jacobian(x).completeOrthogonalDecomposition().solve(values(x));
    x -= dx;
    // Converged (or stuck): further steps only move x by rounding.
    if (!(dx.lpNorm<Eigen::Infinity>() > 1e-15 * (1 + x.lpNorm<Eigen::Infinity>()))) break;
  }
  return x;
}

Eigen::VectorXd centre(const Box& b) {
  Eigen::VectorXd c(b.size());
  const NearestScope nearest;
  for (size_t i = 0; i < b.size(); ++i) c(i) = nearest.median(b[i]);
  return c;
}

std::vector<int> independent_rows(const Eigen::MatrixXd& j) {
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(j.transpose());
  std::vector<int> rows;
  for (int k = 0; k < j.cols(); ++k) rows.push_back(qr.colsPermutation().indices()(k));
  std::sort(rows.begin(), rows.end());
  return rows;
}

}  // namespace linkbox::newton
