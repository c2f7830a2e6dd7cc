#pragma once
// The reference LP backend: CGAL's exact QP solver (number type Gmpzf) on the same LP,
// read as rationals. Slow (lib/README.md: 0.05-8 s per LP on a ~60-column relaxation), so it is
// the oracle in tests and a selectable strategy, not the default. All CGAL headers stay in
// exact_lp.cpp.
#include "prune/lp/lp_solver.hpp"

namespace linkbox::prune::lp {

class ExactLp final : public LpSolver {
 public:
  std::string name() const override { return "exact"; }
  void load(const LinearProgram& program) override { program_ = program; }
  void set_column_bounds(int col, double lo, double hi) override {
    program_.col_lo[col] = lo;
    program_.col_hi[col] = hi;
  }
  // The exact optimum rounded down to a double (the largest double <= the optimum).
  LpBound minimize(int col) override;
  // The exact optimum rounded up (the smallest double >= the optimum).
  LpBound maximize(int col) override;

 private:
  LinearProgram program_;
};

}  // namespace linkbox::prune::lp
