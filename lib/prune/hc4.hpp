#pragma once
// HC4-revise on sums of monomials (forward evaluation, backward projection onto each
// variable), the classic constraint-propagation baseline. Every occurrence x^e is projected
// (e-th roots: both branches for even e). Equations project the sum onto
// 0, inequalities g <= 0 (or < 0) onto (-inf, 0]: a box where g > 0 throughout is empty.
// Links y = f(a) are revised after them (prune/links.hpp).
#include "model/polynomial.hpp"
#include "prune/contractor.hpp"

namespace linkbox::prune {

class Hc4 final : public Contractor {
 public:
  // Arith::float_unverified: the unverified variant (midpoint coefficients, nearest rounding).
  explicit Hc4(const std::vector<model::Polynomial>& equations, Arith arith = Arith::verified,
               const std::vector<model::Inequality>& inequalities = {}, std::vector<model::Link> links = {});
  std::string name() const override { return arith_ == Arith::verified ? "hc4" : "hc4-float"; }
  Outcome contract(Box& box) override;
  std::unique_ptr<Contractor> clone() const override;
  void add_work(Counters& counters) const override;
  double call_operations() const { return call_operations_; }  // what one contract() costs
  // call_operations() of the contractor built from these, without building it.
  static double call_operations_of(const std::vector<model::Polynomial>& equations,
                                   const std::vector<model::Inequality>& inequalities, size_t links);

 private:
  struct Term {
    Interval coef;
    model::Powers powers;
  };
  std::vector<std::vector<Term>> equations_;  // then the inequalities' g
  size_t equation_count_ = 0;
  std::vector<char> strict_;  // per inequality
  std::vector<model::Link> links_;
  std::vector<FastInterval> value_, prefix_, suffix_;  // scratch
  Arith arith_;
  double call_operations_ = 0, operations_ = 0;
  Outcome revise(Box& box);
};

}  // namespace linkbox::prune
