#include "newton/float_system.hpp"

#include "newton/square_system.hpp"

#include <Eigen/QR>

#include <algorithm>

namespace linkbox::newton {

FloatSystem::FloatSystem(const std::vector<model::Polynomial>& f, size_t unknowns) : f_(f), df_(f.size()) {
  for (size_t i = 0; i < f.size(); ++i)
    for (size_t k = 0; k < unknowns; ++k) df_[i].push_back(f[i].derivative(static_cast<int>(k)));
}

Eigen::VectorXd FloatSystem::values(const Eigen::VectorXd& x) const {
  const Box p = point_box(x);
  Eigen::VectorXd v(f_.size());
  for (size_t i = 0; i < f_.size(); ++i) v(i) = median(f_[i].eval(p));
  return v;
}

Eigen::MatrixXd FloatSystem::jacobian(const Eigen::VectorXd& x) const {
  const Box p = point_box(x);
  Eigen::MatrixXd j(f_.size(), x.size());
  for (size_t i = 0; i < f_.size(); ++i)
    for (int k = 0; k < x.size(); ++k) j(i, k) = median(df_[i][k].eval(p));
  return j;
}

Eigen::VectorXd FloatSystem::solve_from(Eigen::VectorXd x) const {
  for (int it = 0; it < 30; ++it) x -= jacobian(x).completeOrthogonalDecomposition().solve(values(x));
  return x;
}

Eigen::VectorXd centre(const Box& b) {
  Eigen::VectorXd c(b.size());
  for (size_t i = 0; i < b.size(); ++i) c(i) = median(b[i]);
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
