#pragma once
// The LP as the float solver sees it: each finite column rewritten as x = shift + scale * u
// with u in [-1, 1]. On a tiny box (width 1e-10, far below CLP's 1e-7 feasibility tolerance)
// CLP otherwise stops at any vertex and its duals give a weak bound. The rewrite is plain
// floating point and only steers the float solver: row multipliers mean the same thing in
// both forms, and the rigorous bound is always evaluated on the original LP.
#include "prune/lp/linear_program.hpp"

#include <vector>

namespace linkbox::prune::lp {

struct Centring {
  std::vector<double> shift, scale;  // per column; (0, 1) for an infinite or fixed column

  double to_u(int col, double x) const { return (x - shift[col]) / scale[col]; }
};

LinearProgram centre_columns(const LinearProgram& lp, Centring& centring);

}  // namespace linkbox::prune::lp
