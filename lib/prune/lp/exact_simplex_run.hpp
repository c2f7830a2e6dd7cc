#pragma once
// One ExactSimplex::solve, phase by phase (private to exact_simplex*.cpp). Each pass over the
// current basis factors it, computes the reduced costs (dual feasibility) and the basic
// solution (primal feasibility), both exactly, and then either stops (optimal, infeasible,
// failed) or takes one pivot: a primal simplex pivot while the basis is dual infeasible, a
// dual simplex pivot while it is primal infeasible, and when it is both, the violated bounds
// are moved out to the current values once, so that primal pivots can run.
//
// Values are kept as integers over the basis determinant and powers of two (dyadic.hpp): each
// quantity's comment gives its scale.
#include "prune/lp/exact_simplex.hpp"
#include "prune/lp/exact_simplex_data.hpp"

#include <gmpxx.h>

#include <utility>
#include <vector>

namespace linkbox::prune::lp {

class ExactSimplex::Run {
 public:
  // min sense * x[col] over `d` (its implied row bounds current).
  Run(Data& d, int col, double sense, int max_pivots);
  ~Run() { restore(); }  // whichever way solve returns, the LP's bounds are its own again
  Run(const Run&) = delete;
  Run& operator=(const Run&) = delete;

  Result solve(const std::vector<BasisStatus>& cols, const std::vector<BasisStatus>& rows);

  // Pivots before Bland's rule takes over (it cannot cycle, but it is slow); the choice is
  // discussed in papers/decisions/exact-lp.md.
  static constexpr int kBlandAfter = 50;

 private:
  using Failure = Result::Failure;
  Result fail(Failure why) {
    result.failure = why;
    return result;
  }

  // The starting basis (exact_simplex_run.cpp).
  bool start(const std::vector<BasisStatus>& cols, const std::vector<BasisStatus>& rows);
  int common_shift() const;
  double bound_of(int v) const { return st[v] == BasisStatus::at_lower ? d.lo[v] : d.hi[v]; }
  void restore();
  // One pass over the current basis (exact_simplex_run.cpp).
  bool index_basis();
  bool factor_basis();
  void reduced_costs();
  void choose_primal_entering();
  void basic_solution();
  void check_bounds(int v);
  void choose_leaving();
  Result optimum();
  void relax_violated_bounds();
  // The pivots (exact_pivots.cpp).
  void primal_column(int v);
  bool primal_pivot(int v);
  void tableau_row();
  void choose_dual_entering();
  Result infeasible();
  // LINKBOX_EXACT_TRACE=1: each pivot on stderr (diagnostics).
  void trace_pivot() const;
  void trace_dual_pivot() const;
  void trace_infeasible() const;

  Data& d;
  const int n, m, total;
  const int col;
  const double sense;
  const int max_pivots;
  mpz_class& t;  // scratch
  mpz_class& u;  // scratch
  Result result;

  std::vector<BasisStatus> st;  // one status per variable; nonbasic ones at a finite bound
  // Every value below is an integer over a power of two 2^g common to all bounds.
  int g = 0;
  // Bounds moved out to a primal infeasible basic variable's value, so that primal simplex
  // pivots can run from a basis that is neither primal nor dual feasible (variable, side,
  // true bound); put back once the basis is dual feasible, before the dual simplex.
  std::vector<std::pair<int, double>> moved_lo, moved_hi;
  std::vector<std::pair<int, bool>> violated;  // basic variables out of bounds: (variable, below)

  // The current pass.
  int pivots = 0;
  std::vector<int> basic_cols, nonbasic_rows, col_pos, row_pos;
  int k = 0;  // basic columns = nonbasic rows: the basis matrix is k x k
  mpz_class& dual_det;  // |det'| of the basis for the duals
  bool flip_dual = false;
  mpz_class& det;  // |det| of the basis for the basic solution
  int enter = -1;  // a nonbasic variable to enter the basis, or -1
  double most = 0;  // its reduced cost's log2 size
  int leave = -1;  // a basic variable to leave it, or -1
  bool leave_up = false;  // it must rise to its lower bound
  double worst = 0;  // its violation's log2 size
  int row_shift = 0;  // the dual simplex row's scale
};

}  // namespace linkbox::prune::lp
