#pragma once
// Neumaier-Shcherbina post-processing: a rigorous bound on an LP optimum from ANY row
// multipliers y, typically a float solver's approximate dual. Because the bound holds for
// every y, a wrong or garbage dual only weakens it, never makes it unsound.
//
// For min c^T x subject to row_lo <= A x <= row_hi, x in X (the column bounds):
//   c^T x = y^T A x + (c - A^T y)^T x
//        >= sum_i (y_i >= 0 ? y_i row_lo_i : y_i row_hi_i) + inf((c - A^T y) . X)
// evaluated in outward-rounded interval arithmetic. A y_i whose needed row bound is
// infinite is treated as zero.
#include "prune/lp/linear_program.hpp"

#include <span>
#include <utility>

namespace linkbox::prune::lp {

// Rigorous lower bound on min c^T x, c given sparsely (column, coefficient). `y` has one
// entry per row. Returns -inf when the bound is unusable (an infinite column bound meets a
// non-zero reduced cost).
double dual_lower_bound(const LinearProgram& program, std::span<const double> y,
                        std::span<const std::pair<int, double>> objective);

// True when y is a checked Farkas certificate: the bound above with c = 0 is > 0, so no x
// in X satisfies the rows.
bool proves_infeasible(const LinearProgram& program, std::span<const double> y);

}  // namespace linkbox::prune::lp
