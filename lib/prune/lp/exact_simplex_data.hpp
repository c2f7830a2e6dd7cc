#pragma once
// The LP as ExactSimplex holds it (private to exact_simplex*.cpp): its rows scaled to
// integers, the bounds of every variable, and the exact workspace kept between solves.
#include "interval/interval.hpp"
#include "prune/lp/exact_simplex.hpp"
#include "prune/lp/integer_lu.hpp"

#include <gmpxx.h>

#include <vector>

namespace linkbox::prune::lp {

struct ExactSimplex::Data {
  int n = 0, m = 0;
  std::vector<int> row_start, index;
  std::vector<double> value;
  // Row i times 2^shift[i], an integer row (shift: the lowest bit of its coefficients).
  std::vector<mpz_class> scaled;
  std::vector<int> shift;
  // Bounds of the n + m variables (columns, then row activities), +-inf when absent.
  std::vector<double> lo, hi;
  // The rows' own bounds; lo/hi box each row further by the range a_i . x takes over the
  // column box (rounded outward, so implied by the box): with every variable boxed, any
  // reduced cost of the wrong sign is repaired by moving its variable to the other bound,
  // and the dual simplex alone restores optimality. Redundant rows change no optimum.
  std::vector<double> row_lo, row_hi;
  bool implied_stale = true;  // a column bound was widened since the implied ones were set
  std::vector<char> narrow;   // per variable: flipped, not pivoted, when its reduced cost is wrong

  // Sets the rows' lo/hi (implied bounds included) and `narrow` for the current column box.
  void set_row_bounds();

  IntegerLu lu;  // the basis matrix
  // Workspace, kept between solves to spare allocations.
  std::vector<mpz_class> rhs, x, c, z, red, alpha, num;
  std::vector<int> red_exp, alpha_exp, num_exp;
  mpz_class t, u, dual_det, primal_det;

  bool has_lo(int v) const { return lo[v] != -kInf; }
  bool has_hi(int v) const { return hi[v] != kInf; }
  bool fixed(int v) const { return lo[v] == hi[v]; }
};

}  // namespace linkbox::prune::lp
