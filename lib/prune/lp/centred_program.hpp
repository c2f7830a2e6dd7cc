#pragma once
// The LP as the float solver sees it: each finite column rewritten as x = shift + scale * u
// with u in [-1, 1]. On a tiny box (width 1e-10, far below CLP's 1e-7 feasibility tolerance)
// CLP otherwise stops at any vertex and its duals give a weak bound. The rewrite is plain
// floating point and only steers the float solver; the rigorous bound is always evaluated on
// the original LP. Each row is then multiplied by a power of two that brings its largest
// coefficient near 1 (CLP's own scaling is off: it made CLP call feasible relaxations of
// bicyclohexane infeasible, while without any row scaling its absolute tolerances swamp the
// rows of a 1e-8-wide box). A multiplier y of a centred row is r * y for the original row.
#include "prune/lp/linear_program.hpp"

#include <vector>

namespace linkbox::prune::lp {

struct Centring {
  std::vector<double> shift, scale;  // per column; (0, 1) for an infinite or fixed column
  std::vector<double> row_scale;     // per row, a power of two

  double to_u(int col, double x) const { return (x - shift[col]) / scale[col]; }
};

LinearProgram centre_columns(const LinearProgram& lp, Centring& centring);

// Row multipliers of the centred LP as multipliers of the original rows.
void to_original_rows(const Centring& centring, std::vector<double>& y);

}  // namespace linkbox::prune::lp
