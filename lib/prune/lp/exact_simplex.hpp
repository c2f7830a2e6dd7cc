#pragma once
// The exact half of the exact LP backend: a bounded-variable simplex in rational arithmetic
// (GMP) that starts from a given basis, normally CLP's optimal one. Every double of the LP is
// read exactly. A basis whose basic solution is primal feasible and whose multipliers are dual
// feasible, both checked exactly, is an optimality certificate: the optimum is then known
// exactly, whatever produced the basis. When the checks fail, a few exact pivots repair the
// basis (dual simplex while it is dual feasible, primal simplex while primal feasible); a
// dual-simplex row with no entering candidate says the LP is infeasible, and its multipliers
// are returned for the caller to check as a Farkas certificate (ExactLp trusts only that).
//
// Variables are the columns x_j and the row activities r_i = a_i . x, each with its bounds.
// With k basic columns the basis fixes k nonbasic rows, and the basic columns solve the
// k x k system A[nonbasic rows, basic columns] x_B = r_N - A[nonbasic rows, nonbasic cols] x_N;
// the basic rows follow by products. k is at most the number of columns, far below the
// number of rows of the full basis, and the system is sparse.
//
// Integers, not rationals: the LP's doubles are integers times powers of two, so each row is
// scaled to integers (dyadic.hpp) and the basis systems are solved fraction-free
// (integer_lu.hpp): every division is exact, a solution comes out as integers over one common
// denominator, and signs and comparisons need no gcd (papers/decisions/exact-lp.md).
//
// GMP stays in the .cpp files (the data lives behind a pointer); the solve itself is
// exact_simplex_run.hpp.
#include "prune/lp/clp_core.hpp"
#include "prune/lp/linear_program.hpp"

#include <memory>
#include <span>
#include <vector>

namespace linkbox::prune::lp {

class ExactSimplex {
 public:
  ExactSimplex();
  ~ExactSimplex();
  ExactSimplex(const ExactSimplex&) = delete;
  ExactSimplex& operator=(const ExactSimplex&) = delete;

  // Converts the LP's data to rationals once; later solves reuse it.
  void load(const LinearProgram& program);
  void set_column_bounds(int col, double lo, double hi);

  struct Result {
    enum Kind {
      optimal,     // down/up: the exact optimum of sense * x[col] rounded down and up
      infeasible,  // an exact dual-simplex row found no entering variable (the caller checks
                   // `farkas` before trusting it)
      failed,      // no certificate within the pivot budget (or a singular basis)
    } kind = failed;
    double down = 0, up = 0;
    int pivots = 0;  // exact pivots taken
    // The starting basis as found: basic columns, nonbasic variables moved to their other
    // bound for dual feasibility, violated bounds after that, wrong-signed reduced costs left.
    int size = 0, flips = 0, primal_violations = 0, dual_violations = 0;
    // Why it failed (numbered for diagnostics that count them).
    enum class Failure {
      none = 0,
      not_a_vertex = 1,                // a free nonbasic variable, or not a basis's size
      singular_basis = 2,
      primal_and_dual_infeasible = 3,  // again, after the violated bounds were moved out once
      pivot_budget = 4,                // `max_pivots` spent
      unbounded = 5,                   // a primal simplex ray (only with infinite bounds)
    } failure = Failure::none;
    int relaxations = 0;  // times violated bounds were moved out for primal pivots
    // infeasible: row multipliers (rounded to doubles) of the dual simplex row that found
    // it, a candidate Farkas certificate (either sign) for proves_infeasible.
    std::vector<double> farkas;
  };
  // min sense * x[col] from the basis (cols, rows) (ClpCore::basis), with at most
  // `max_pivots` exact pivots.
  Result solve(int col, double sense, std::vector<BasisStatus> cols, std::vector<BasisStatus> rows,
               int max_pivots);

  // True when y is a Farkas certificate in exact arithmetic: with y_i >= 0 read against
  // row_lo and y_i < 0 against row_hi, the largest value of (y^T A) x over the column box is
  // below sum y_i b_i. Non-finite y_i, or ones whose needed row bound is infinite, count 0.
  bool proves_infeasible(std::span<const double> y) const;

 private:
  struct Data;  // the LP in scaled integers and the workspace (exact_simplex_data.hpp)
  class Run;    // one solve, phase by phase (exact_simplex_run.hpp)
  std::unique_ptr<Data> d_;
};

}  // namespace linkbox::prune::lp
