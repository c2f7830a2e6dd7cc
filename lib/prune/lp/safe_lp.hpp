#pragma once
// The default LP backend: CLP's dual simplex, warm-started across the successive objectives
// of one shrink (clp_core.hpp), with every answer made rigorous afterwards (safe_bound.hpp).
// CLP only proposes multipliers; the interval check decides.
#include "prune/lp/clp_core.hpp"
#include "prune/lp/lp_solver.hpp"

namespace linkbox::prune::lp {

class SafeLp final : public LpSolver {
 public:
  // trust_float: return CLP's own optimum and infeasibility verdict, unchecked (--arith float).
  explicit SafeLp(bool trust_float = false);
  std::string name() const override { return trust_float_ ? "float" : "safe"; }
  void load(const LinearProgram& program) override { clp_.load(program); }
  void set_column_bounds(int col, double lo, double hi) override { clp_.set_column_bounds(col, lo, hi); }
  LpBound minimize(int col) override;
  LpBound maximize(int col) override;

  bool last_point(std::vector<double>& x) const override { return clp_.point(x); }
  long iterations() const override { return clp_.iterations(); }
  double operations() const override { return clp_.operations(); }

 private:
  LpBound solve(int col, double sense);  // min of sense * x[col], sense = +-1

  ClpCore clp_;
  bool trust_float_ = false;
};

// The rigorous half of SafeLp, for any backend that ran ClpCore::solve: a checked Farkas
// certificate (CLP's ray, else the elastic LP's duals) or the N-S bound from CLP's duals, on
// min sense * x[col]. The value is in terms of sense * x[col].
LpBound safe_bound_after(const ClpCore& clp, ClpCore::Finish finish, int col, double sense);

}  // namespace linkbox::prune::lp
