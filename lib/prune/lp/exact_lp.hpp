#pragma once
// The exact LP backend: every answer is the exact optimum of the LP as loaded, rounded
// outward to a double, or an exact infeasibility proof. CLP solves in floating point
// (warm-started, clp_core.hpp); its final basis is then checked in rational arithmetic
// (exact_simplex.hpp): primal and dual feasibility together certify the optimum. A basis
// that fails the check is repaired by a few exact pivots; CLP's infeasibility verdict is
// checked as a Farkas certificate in rationals. Whatever stays undecided goes to CGAL's exact
// QP solver from scratch (cgal_lp.hpp), so the answer never rests on floating point.
// paths() counts which way each LP went.
#include "prune/lp/clp_core.hpp"
#include "prune/lp/exact_simplex.hpp"
#include "prune/lp/lp_solver.hpp"

namespace linkbox::prune::lp {

class ExactLp final : public LpSolver {
 public:
  ExactLp();
  std::string name() const override { return "exact"; }
  void load(const LinearProgram& program) override;
  void set_column_bounds(int col, double lo, double hi) override;
  // The exact optimum rounded down to a double (the largest double <= the optimum).
  LpBound minimize(int col) override { return solve(col, 1.0); }
  // The exact optimum rounded up (the smallest double >= the optimum).
  LpBound maximize(int col) override { return solve(col, -1.0); }

  bool last_point(std::vector<double>& x) const override { return clp_.point(x); }
  long iterations() const override { return clp_.iterations(); }
  double operations() const override { return clp_.operations(); }
  LpPaths paths() const override { return paths_; }

  // Exact pivots allowed from CLP's basis before CGAL takes over: an exact pivot costs far
  // less than a CGAL solve (figures in papers/decisions/exact-lp.md).
  static constexpr int kMaxPivots = 400;
  // CLP's tolerances for the exact backend, tighter than CLP's defaults, so that fewer of the
  // bases CLP calls optimal need exact repairs (papers/decisions/exact-lp.md).
  static constexpr double kPrimalTolerance = 1e-11, kDualTolerance = 1e-10;

 private:
  LpBound solve(int col, double sense);
  // A candidate Farkas certificate of either sign (CLP's ray convention changed across
  // versions; a dual simplex row's multipliers come with the leaving row's sign), checked
  // exactly; y is left negated when only -y proves it.
  bool proves_infeasible_either_sign(std::vector<double>& y) const;

  ClpCore clp_;
  ExactSimplex exact_;
  LpPaths paths_;
  std::vector<BasisStatus> cols_, rows_;
};

}  // namespace linkbox::prune::lp
