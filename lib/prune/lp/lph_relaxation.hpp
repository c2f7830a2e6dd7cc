#pragma once
// The LP relaxation of an L/P/H system over a box (iterated-LP paper, Section III and
// Algorithm 2 lines 1-7), built so that the LP's feasible set provably contains every point
// of the box that satisfies the system:
//   - each linear equation with its interval coefficients replaced by their midpoints, the
//     remainder moved into the row bounds;
//   - each q = x^2: the secant (q below it) and tangents at both ends of x and at its midpoint
//     (the one parallel to the secant; q above them);
//   - each b = x*y: the four planes of the tetrahedron through the lifted corners of the
//     x-y rectangle (McCormick).
//   - each inequality (linear in the lifted variables): its half-space, as the equations.
// Every row is written  sum a_j v_j in [lo, hi]  with double a_j and lo/hi computed in
// outward-rounded interval arithmetic from the true (interval) coefficients, so rounding in
// a_j is paid for in the bounds. One LP column per system variable, bounded by the box.
#include "interval/box.hpp"
#include "model/lph.hpp"
#include "prune/lp/linear_program.hpp"

#include <vector>

namespace linkbox::prune::lp {

struct IntervalTerm {
  int var;
  Interval coef;  // encloses the true coefficient
};

enum class RowSense { at_most, at_least, equal };

// Appends a row that every point v of `box` satisfying  sum A_j v_j (sense) B  for some true
// A_j in terms[j].coef and B in rhs satisfies too. Repeated variables are merged. A row
// whose data is not finite is skipped (dropping a relaxation row is always sound).
void add_enclosing_row(LinearProgram& lp, const Box& box, std::vector<IntervalTerm> terms,
                       const Interval& rhs, RowSense sense);

// Columns = the box's variables in order, rows = the relaxation of `system` over `box`.
// Rows that need a finite range (secant, tetrahedron) are left out when the range is not.
LinearProgram build_lph_relaxation(const model::LphSystem& system, const Box& box);

}  // namespace linkbox::prune::lp
