#include "prune/lp/exact_lp.hpp"

#include "interval/interval.hpp"
#include "prune/lp/cgal_lp.hpp"

namespace linkbox::prune::lp {

void ExactLp::load(const LinearProgram& program) {
  clp_.load(program);
  exact_.load(program);
}

void ExactLp::set_column_bounds(int col, double lo, double hi) {
  clp_.set_column_bounds(col, lo, hi);
  exact_.set_column_bounds(col, lo, hi);
}

LpBound ExactLp::solve(int col, double sense) {
  const ClpCore::Finish finish = clp_.solve(col, sense);
  const LpBound infeasible{LpStatus::infeasible, sense > 0 ? kInf : -kInf};
  std::vector<double> y;
  // CLP's ray (either sign: the convention changed across CLP versions) is checked first: a
  // Farkas certificate in rationals is the cheapest proof.
  if (finish == ClpCore::Finish::infeasible && clp_.ray(y)) {
    bool proved = exact_.proves_infeasible(y);
    if (!proved) {
      for (double& v : y) v = -v;
      proved = exact_.proves_infeasible(y);
    }
    if (proved) {
      ++paths_.farkas;
      return infeasible;
    }
  }
  // CLP's last basis, optimal or not: checked, else repaired by exact pivots (a dual simplex
  // row with no entering variable proves infeasibility).
  clp_.basis(cols_, rows_);
  const ExactSimplex::Result r = exact_.solve(col, sense, cols_, rows_, kMaxPivots);
  paths_.pivots += r.pivots;
  if (r.kind == ExactSimplex::Result::optimal) {
    ++(r.pivots ? paths_.repaired : paths_.basis);
    // r.down encloses the optimum of sense * x[col] from below; max x = -min(-x).
    return LpBound{LpStatus::bounded, sense > 0 ? r.down : -r.down};
  }
  if (r.kind == ExactSimplex::Result::infeasible) {
    ++paths_.farkas;
    return infeasible;
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
