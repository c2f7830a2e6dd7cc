#include "prune/lp/exact_lp.hpp"

#include "interval/interval.hpp"
#include "prune/lp/cgal_lp.hpp"
#include "prune/lp/safe_lp.hpp"

namespace linkbox::prune::lp {

ExactLp::ExactLp() { clp_.set_tolerances(kPrimalTolerance, kDualTolerance); }

void ExactLp::load(const LinearProgram& program) {
  clp_.load(program);
  exact_.load(program);
}

void ExactLp::set_column_bounds(int col, double lo, double hi) {
  clp_.set_column_bounds(col, lo, hi);
  exact_.set_column_bounds(col, lo, hi);
}

bool ExactLp::proves_infeasible_either_sign(std::vector<double>& y) const {
  if (exact_.proves_infeasible(y)) return true;
  for (double& v : y) v = -v;
  return exact_.proves_infeasible(y);
}

LpBound ExactLp::solve(int col, double sense) {
  const ClpCore::Finish finish = clp_.solve(col, sense);
  const LpBound infeasible{LpStatus::infeasible, sense > 0 ? kInf : -kInf};
  std::vector<double> y;
  // CLP's ray (either sign: the convention changed across CLP versions) is checked first: a
  // Farkas certificate in rationals is the cheapest proof.
  if (finish == ClpCore::Finish::infeasible && clp_.ray(y) && proves_infeasible_either_sign(y)) {
    ++paths_.farkas;
    return infeasible;
  }
  // CLP's last basis, optimal or not: checked, else repaired by exact pivots (a dual simplex
  // row with no entering variable says infeasible; its multipliers are checked as a Farkas
  // certificate before that is believed).
  clp_.basis(cols_, rows_);
  const ExactSimplex::Result r = exact_.solve(col, sense, cols_, rows_, kMaxPivots);
  paths_.pivots += r.pivots;
  // A consistency guard: CLP's duals give a rigorous lower bound on min sense * x[col]
  // (Neumaier-Shcherbina, safe_lp.hpp) that the exact optimum rounded down can never be below;
  // an answer below it goes to CGAL. It costs one such bound (its history:
  // papers/decisions/exact-lp.md).
  if (r.kind == ExactSimplex::Result::optimal && finish == ClpCore::Finish::optimal) {
    const LpBound safe = safe_bound_after(clp_, finish, col, sense);
    if (safe.status == LpStatus::infeasible || (safe.status == LpStatus::bounded && r.down < safe.value)) {
      ++paths_.fallback;
      return to_bound(cgal_minimum(clp_.program(), col, sense), sense);
    }
  }
  if (r.kind == ExactSimplex::Result::optimal) {
    ++(r.pivots ? paths_.repaired : paths_.basis);
    // r.down encloses the optimum of sense * x[col] from below; max x = -min(-x).
    return LpBound{LpStatus::bounded, sense > 0 ? r.down : -r.down};
  }
  if (r.kind == ExactSimplex::Result::infeasible) {
    // Trusted only as a checked Farkas certificate (the oracle once caught the dual simplex
    // claiming an LP empty that CGAL solved); else CGAL decides below.
    std::vector<double> yr = r.farkas;
    if (proves_infeasible_either_sign(yr)) {
      ++paths_.farkas;
      return infeasible;
    }
  }
  // The elastic LP's duals, when CLP did not finish optimal.
  if (finish != ClpCore::Finish::optimal && exact_.proves_infeasible(clp_.elastic_duals())) {
    ++paths_.farkas;
    return infeasible;
  }
  ++paths_.fallback;
  return to_bound(cgal_minimum(clp_.program(), col, sense), sense);
}

}  // namespace linkbox::prune::lp
