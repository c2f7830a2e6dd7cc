#include "prune/lp/tighten.hpp"

#include <vector>

namespace linkbox::prune::lp {

namespace {

// Narrows box[var] by a rigorous bound of the LP; false when the bound proves it empty.
bool narrow(LpSolver& solver, int var, const LpBound& bound, bool minimum, Box& box) {
  if (bound.status == LpStatus::infeasible) return false;
  if (bound.status != LpStatus::bounded) return true;
  Interval& range = box[var];
  if (minimum && bound.value > range.lower()) {
    if (bound.value > range.upper()) return false;  // a rigorous bound beyond the box
    range = Interval(bound.value, range.upper());
  } else if (!minimum && bound.value < range.upper()) {
    if (bound.value < range.lower()) return false;
    range = Interval(range.lower(), bound.value);
  } else {
    return true;
  }
  solver.set_column_bounds(var, range.lower(), range.upper());
  return true;
}

}  // namespace

bool tighten_columns(LpSolver& solver, std::span<const int> columns, Box& box, long& lps_solved,
                     const std::function<bool()>* stop) {
  std::vector<char> low_reached(box.size(), 0), high_reached(box.size(), 0);
  std::vector<double> point;
  auto solved = [&] {
    ++lps_solved;
    if (!solver.last_point(point)) return;
    for (int j : columns) {
      const double tolerance = 1e-9 * (box[j].upper() - box[j].lower());
      low_reached[j] |= point[j] <= box[j].lower() + tolerance;
      high_reached[j] |= point[j] >= box[j].upper() - tolerance;
    }
  };
  for (int var : columns) {
    if (stop && (*stop)()) break;
    if (!low_reached[var]) {
      const LpBound low = solver.minimize(var);
      solved();
      if (!narrow(solver, var, low, true, box)) return false;
    }
    if (!high_reached[var]) {
      const LpBound high = solver.maximize(var);
      solved();
      if (!narrow(solver, var, high, false, box)) return false;
    }
  }
  return true;
}

}  // namespace linkbox::prune::lp
