#pragma once
// A polynomial system of any shape in float arithmetic (midpoints of interval values at a
// point). It only chooses where to look and which equations to keep; it proves nothing.
#include "model/compiled.hpp"
#include "model/polynomial.hpp"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace linkbox::newton {

class FloatSystem {
 public:
  FloatSystem(const std::vector<model::Polynomial>& f, size_t unknowns);
  explicit FloatSystem(std::shared_ptr<const model::CompiledSystem> f) : f_(std::move(f)) {}
  Eigen::VectorXd values(const Eigen::VectorXd& x) const;
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& x) const;
  // Gauss-Newton with the pseudo-inverse: onto a curve, or the least-squares point of an
  // overdetermined system.
  Eigen::VectorXd solve_from(Eigen::VectorXd x) const;

 private:
  std::shared_ptr<const model::CompiledSystem> f_;
};

Eigen::VectorXd centre(const Box& b);  // midpoints

// The rows of `j` (at least as many as columns) that a column-pivoted QR of j^T keeps first:
// j.cols() equations whose Jacobian is best conditioned, sorted. A choice, not a proof: any
// square subsystem's roots contain the full system's.
std::vector<int> independent_rows(const Eigen::MatrixXd& j);

}  // namespace linkbox::newton
