#pragma once
// CGAL's exact QP solver (number type Gmpzf) on the same LP, read as rationals, from scratch
// for every objective. Slow (lib/README.md: 0.05-8 s per LP on a ~60-column relaxation), so
// it is the independent oracle in tests, the fall-back of the exact backend and the
// selectable `--lp cgal`, not a default. All CGAL headers stay in cgal_lp.cpp.
#include "prune/lp/lp_solver.hpp"

#include <limits>

namespace linkbox::prune::lp {

// The exact minimum of sense * x[col] (sense = +-1) over `program`: `bounded` with the
// optimum rounded down (`down`, the largest double <= it) and up; `infeasible`; or
// `unknown` when the LP is unbounded (only with infinite column bounds; down = -inf).
struct ExactOptimum {
  LpStatus status = LpStatus::unknown;
  double down = -std::numeric_limits<double>::infinity(), up = std::numeric_limits<double>::infinity();
};
ExactOptimum cgal_minimum(const LinearProgram& program, int col, double sense);

class CgalLp final : public LpSolver {
 public:
  std::string name() const override { return "cgal"; }
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

// The LP bound a minimize (sense 1) or maximize (sense -1) reports for an exact optimum of
// sense * x[col].
LpBound to_bound(const ExactOptimum& e, double sense);

}  // namespace linkbox::prune::lp
