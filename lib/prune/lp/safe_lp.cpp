#include "prune/lp/safe_lp.hpp"

#include "interval/interval.hpp"
#include "prune/lp/safe_bound.hpp"

#include <vector>

namespace linkbox::prune::lp {

SafeLp::SafeLp(bool trust_float) : trust_float_(trust_float) {}

LpBound SafeLp::minimize(int col) { return solve(col, 1.0); }

LpBound SafeLp::maximize(int col) {
  LpBound b = solve(col, -1.0);
  b.value = -b.value;  // max x = -min(-x): a lower bound on -x negates to an upper bound on x
  return b;
}

// Bounds min sense * x[col]; the returned value is in terms of sense * x[col].
LpBound SafeLp::solve(int col, double sense) {
  const ClpCore::Finish finish = clp_.solve(col, sense);
  if (trust_float_) {
    const LinearProgram& lp = clp_.program();
    if (finish == ClpCore::Finish::infeasible) return LpBound{LpStatus::infeasible, kInf};
    std::vector<double> x;
    if (finish != ClpCore::Finish::optimal || !clp_.point(x))
      return LpBound{LpStatus::unknown, sense > 0 ? lp.col_lo[col] : -lp.col_hi[col]};
    return LpBound{LpStatus::bounded, sense * x[col]};
  }
  return safe_bound_after(clp_, finish, col, sense);
}

LpBound safe_bound_after(const ClpCore& clp, ClpCore::Finish finish, int col, double sense) {
  const LinearProgram& program = clp.program();
  const double trivial = sense > 0 ? program.col_lo[col] : -program.col_hi[col];
  const double other_end = sense > 0 ? program.col_hi[col] : -program.col_lo[col];  // max of sense*x
  const std::pair<int, double> objective[] = {{col, sense}};
  const LpBound infeasible{LpStatus::infeasible, kInf};
  const bool claims_infeasible = finish == ClpCore::Finish::infeasible;
  if (claims_infeasible) {
    std::vector<double> y;
    if (clp.ray(y)) {
      if (proves_infeasible(program, y)) return infeasible;
      for (double& v : y) v = -v;
      if (proves_infeasible(program, y)) return infeasible;
    }
  }
  // CLP's rays are often missing or not certificates (about one infeasible LP in ten in the
  // tests), and a stopped or primal-infeasible finish may hide infeasibility: the duals of
  // the elastic (phase-1) LP are then the dependable source.
  if ((claims_infeasible || finish != ClpCore::Finish::optimal || !clp.primal_feasible()) &&
      proves_infeasible(program, clp.elastic_duals()))
    return infeasible;
  double bound = dual_lower_bound(program, clp.duals(), objective);
  // A lower bound on sense*x above its largest value in X proves the LP empty.
  if (bound > other_end) return infeasible;
  // Weak duality holds for any y, so even the duals of an unfinished or wrongly
  // "infeasible" solve give a valid bound. Both are valid lower bounds; keep the better one.
  return LpBound{LpStatus::bounded, bound > trivial ? bound : trivial};
}

}  // namespace linkbox::prune::lp
