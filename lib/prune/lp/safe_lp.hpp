#pragma once
// The default LP backend: CLP's dual simplex, warm-started across the successive objectives
// of one shrink, with every answer made rigorous afterwards (safe_bound.hpp). CLP only
// proposes multipliers; the interval check decides.
#include "prune/lp/centred_program.hpp"
#include "prune/lp/lp_solver.hpp"

#include <memory>

class ClpSimplex;  // keeps CLP's headers out of every includer

namespace linkbox::prune::lp {

class SafeLp final : public LpSolver {
 public:
  // trust_float: return CLP's own optimum and infeasibility verdict, unchecked (--arith float).
  explicit SafeLp(bool trust_float = false);
  ~SafeLp() override;
  std::string name() const override { return trust_float_ ? "float" : "safe"; }
  void load(const LinearProgram& program) override;
  void set_column_bounds(int col, double lo, double hi) override;
  LpBound minimize(int col) override;
  LpBound maximize(int col) override;

  bool last_point(std::vector<double>& x) const override;
  long iterations() const override { return iterations_; }

 private:
  LpBound solve(int col, double sense);  // min of sense * x[col], sense = +-1
  bool elastic_certificate() const;      // Farkas certificate from a phase-1 LP, checked

  LinearProgram program_;   // as loaded: the rigorous bounds are computed on this one
  LinearProgram centred_;   // the same LP in centred columns: what CLP solves
  Centring centring_;
  std::unique_ptr<ClpSimplex> model_;
  int objective_col_ = -1;  // the single non-zero of CLP's current objective
  long iterations_ = 0;
  bool trust_float_ = false;
};

}  // namespace linkbox::prune::lp
