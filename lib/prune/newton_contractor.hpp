#pragma once
// Interval Newton as a contractor on systems of any shape with at least as many equations as
// unknowns: Hansen-Sengupta (Gauss-Seidel) on the preconditioned system C F(x) = 0, with C
// the inverse (square) or pseudo-inverse (overdetermined) of the midpoint Jacobian, in
// float. For any C the roots of F in X are roots of C F, so X <- X ∩ (its Gauss-Seidel
// image) loses none, and an image disjoint from X proves X empty; C only decides how much
// is removed. A system with fewer equations than unknowns (a curve) gets the range test only.
// Linear definitions of the variables `substitutable` names are substituted out first
// (prune/newton_substitution.hpp). Where the whole midpoint Jacobian of a system that
// separates into blocks is singular, C inverts its regular diagonal blocks instead.
#include "model/compiled.hpp"
#include "prune/contractor.hpp"
#include "prune/newton_substitution.hpp"

#include <vector>

#include <Eigen/Core>

namespace linkbox::prune {

class IntervalNewton final : public Contractor {
 public:
  // Arith::float_unverified evaluates with midpoint coefficients in round-to-nearest (the
  // unverified variant).
  // Links are rows too (model/compiled.hpp).
  IntervalNewton(const std::vector<model::Polynomial>& equations, size_t variables, Arith arith = Arith::verified,
                 const std::vector<model::Link>& links = {}, const std::vector<int>& substitutable = {});
  std::string name() const override { return arith_ == Arith::verified ? "newton" : "newton-float"; }
  Outcome contract(Box& box) override;
  std::unique_ptr<Contractor> clone() const override { return std::make_unique<IntervalNewton>(*this); }
  void add_work(Counters& counters) const override { counters.operations += operations_; }
  double step_operations() const;  // what one contract() costs that reaches Gauss-Seidel
  // step_operations() of the contractor built from these with nothing substituted, without
  // building it (model::CompiledSystem::shape_of).
  static double step_operations_of(const std::vector<model::Polynomial>& equations, size_t variables,
                                   const std::vector<model::Link>& links = {});
  // The last step's image lay strictly inside the box in every coordinate: C F has exactly
  // one root there, so F has at most one. A hint for when to try a certificate; the
  // certificate itself is proved elsewhere.
  bool at_most_one_root() const override { return unique_; }

 private:
  Outcome step(Box& box);
  bool midpoints(const Box& box);          // y_ over Newton's unknowns; false when unbounded
  bool substituted_jacobian(const Box& box);  // z_, and g_ = G' over the segments from z_
  bool precondition();                     // c_ from the midpoint Jacobian; false when singular
  void find_blocks();                      // blocks_
  bool block_precondition();               // c_ from the regular diagonal blocks; false if none
  Outcome gauss_seidel(Box& box);          // with c_, f_ = F at the expansion point
  // Newton's system: the compiled one, or what is left of it after substitution.
  int unknowns() const { return substitution_.empty() ? system_.cols() : substitution_.cols(); }
  int equations() const { return substitution_.empty() ? system_.rows() : substitution_.rows(); }
  int nonzeros() const { return substitution_.empty() ? system_.nonzeros() : substitution_.nonzeros(); }
  int entry_row(int e) const { return substitution_.empty() ? system_.entry_row(e) : substitution_.entry_row(e); }
  int entry_col(int e) const { return substitution_.empty() ? system_.entry_col(e) : substitution_.entry_col(e); }
  const FastInterval* jacobian() const { return substitution_.empty() ? j_.data() : g_.data(); }
  double factor_operations() const;  // the midpoint Jacobian's LU
  double solve_operations() const;   // the rest of a step, once the LU is regular

  struct Block {
    std::vector<int> cols, rows;  // Newton's unknowns and the equations matched to them
  };

  model::CompiledSystem system_;
  NewtonSubstitution substitution_;
  std::vector<Block> blocks_;  // upstream first; empty when the system is one block
  Arith arith_;
  bool unique_ = false;
  double operations_ = 0;
  // Scratch.
  std::vector<FastInterval> f_, j_, g_, a_, b_, d_, diagonal_;
  std::vector<int> live_;  // the rows of C F'(X) whose diagonal entry excludes 0
  Box z_;        // the expansion point, its substituted coordinates at L(y)
  Box widened_;  // the box, each substituted coordinate widened to hold L(y)
  Eigen::MatrixXd jm_, c_;
  std::vector<double> y_;
};

}  // namespace linkbox::prune
