#pragma once
// Interval Newton as a contractor on systems of any shape with at least as many equations as
// unknowns: Hansen-Sengupta (Gauss-Seidel) on the preconditioned system C F(x) = 0, with C
// the inverse (square) or pseudo-inverse (overdetermined) of the midpoint Jacobian, in
// float. For any C the roots of F in X are roots of C F, so X <- X ∩ (its Gauss-Seidel
// image) loses none, and an image disjoint from X proves X empty; C only decides how much
// is removed. A system with fewer equations than unknowns (a curve) gets the range test only.
#include "model/compiled.hpp"
#include "prune/contractor.hpp"

#include <Eigen/Core>

namespace linkbox::prune {

class IntervalNewton final : public Contractor {
 public:
  // Arith::float_unverified evaluates with midpoint coefficients in round-to-nearest (the
  // unverified variant).
  // Links are rows too (model/compiled.hpp).
  IntervalNewton(const std::vector<model::Polynomial>& equations, size_t variables, Arith arith = Arith::verified,
                 const std::vector<model::Link>& links = {});
  std::string name() const override { return arith_ == Arith::verified ? "newton" : "newton-float"; }
  Outcome contract(Box& box) override;
  std::unique_ptr<Contractor> clone() const override { return std::make_unique<IntervalNewton>(*this); }
  void add_work(Counters& counters) const override { counters.operations += operations_; }
  double step_operations() const;  // what one contract() costs that reaches Gauss-Seidel
  // The last step's image lay strictly inside the box in every coordinate: C F has exactly
  // one root there, so F has at most one (a square F: exactly one). A hint for when to try a
  // certificate; the certificate itself is proved elsewhere.
  bool at_most_one_root() const override { return unique_; }

 private:
  Outcome step(Box& box);
  double factor_operations() const;  // the midpoint Jacobian's LU
  double solve_operations() const;   // the rest of a step, once the LU is regular

  model::CompiledSystem system_;
  Arith arith_;
  bool unique_ = false;
  double operations_ = 0;
  // Scratch.
  std::vector<FastInterval> f_, j_, a_, b_, d_;
  Eigen::MatrixXd jm_, c_;
  std::vector<double> y_;
};

}  // namespace linkbox::prune
