#pragma once
// Interval Newton as a contractor on square systems: X <- X ∩ N(X), with the inverse of the
// midpoint Jacobian (float) as preconditioner; N(X) disjoint from X proves X empty. The
// float preconditioner only affects how much is removed: N(X) encloses every root in X
// for any matrix.
#include "prune/contractor.hpp"
#include "newton/interval_newton.hpp"

namespace linkbox::prune {

class IntervalNewton final : public Contractor {
 public:
  // Throws std::invalid_argument unless there are as many equations as variables.
  // Arith::float_unverified evaluates with midpoint coefficients (the unverified variant).
  IntervalNewton(const std::vector<model::Polynomial>& equations, size_t variables, Arith arith = Arith::verified,
                 newton::Method method = newton::Method::hansen_sengupta);
  std::string name() const override { return "newton"; }
  Outcome contract(Box& box) override;
  std::unique_ptr<Contractor> clone() const override { return std::make_unique<IntervalNewton>(*this); }

 private:
  newton::SquareSystem system_;
  newton::Method method_;
};

}  // namespace linkbox::prune
