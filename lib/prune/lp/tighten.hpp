#pragma once
// The bound-tightening loop of an LP contractor (iterated-LP paper, Algorithm 2 lines 8-11):
// each of `columns` minimised and maximised in turn over the loaded LP, each new bound fed to
// the next LPs as the paper's in-place update of the box does. Only the backend's rigorous
// bounds move `box` (lp_solver.hpp).
//
// A column already at its lower (upper) bound in the optimal point of an earlier LP of this
// pass cannot be raised (lowered) by its own LP, which is skipped (Gleixner et al., "Three
// enhancements for optimization-based bound tightening", 2017). A bound tightened since may
// cut that point off, so the skip can forgo a little pruning; skipping an LP is always sound.
#include "interval/box.hpp"
#include "prune/lp/lp_solver.hpp"

#include <functional>
#include <span>
#include <string>

namespace linkbox::prune::lp {

// In which order the bounds are tried. `given`: each column's lower then upper bound, in the
// order of `columns` (the paper's Algorithm 2). `nearest_bound`: next the open bound nearest
// the last LP's optimal point, relative to its column's width, so that each warm-started LP
// starts near its optimum (Gleixner et al.'s greedy order). Either order is sound; they may
// differ in how much a pass prunes, since each bound feeds the LPs after it.
enum class Order { given, nearest_bound };
std::string to_string(Order order);  // "given", "nearest"

// False when the box is proved empty. `stop` (may be null) is asked before each column (each
// LP in nearest-bound order): every bound so far is proved, so stopping there is sound, only
// less tight. `lps_solved` counts the LPs.
bool tighten_columns(LpSolver& solver, std::span<const int> columns, Box& box, long& lps_solved,
                     const std::function<bool()>* stop, Order order = Order::given);

}  // namespace linkbox::prune::lp
