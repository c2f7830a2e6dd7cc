#include "prune/lp/tighten.hpp"

#include <tuple>
#include <utility>
#include <vector>

namespace linkbox::prune::lp {

std::string to_string(Order order) { return order == Order::given ? "given" : "nearest"; }

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

// The LPs of one pass: which bounds are still to be tried, and which the optimal points of
// the LPs so far already reached (those are skipped).
class Pass {
 public:
  Pass(LpSolver& solver, std::span<const int> columns, Box& box, long& lps_solved)
      : solver_(solver), columns_(columns), box_(box), lps_solved_(lps_solved), reached_(2 * box.size(), 0) {}

  bool open(int var, bool minimum) const { return !reached_[2 * var + (minimum ? 0 : 1)]; }

  // Solves the LP of one bound and narrows the box by it; false when the box is proved empty.
  bool tighten(int var, bool minimum) {
    reached_[2 * var + (minimum ? 0 : 1)] = 1;
    const LpBound bound = minimum ? solver_.minimize(var) : solver_.maximize(var);
    ++lps_solved_;
    if (solver_.last_point(point_))
      for (int j : columns_) {
        const double tolerance = 1e-9 * (box_[j].upper() - box_[j].lower());
        reached_[2 * j] |= point_[j] <= box_[j].lower() + tolerance;
        reached_[2 * j + 1] |= point_[j] >= box_[j].upper() - tolerance;
      }
    return narrow(solver_, var, bound, minimum, box_);
  }

  // The open bound nearest the last optimal point, relative to its column's width: its LP
  // starts nearest its optimum. {-1, _} when none is open.
  std::pair<int, bool> nearest_open() const {
    std::pair<int, bool> best{-1, true};
    double best_gap = kInf;
    for (int j : columns_)
      for (bool minimum : {true, false}) {
        if (!open(j, minimum)) continue;
        const double w = box_[j].upper() - box_[j].lower();
        double gap = 0.5;
        if (!point_.empty() && w > 0) gap = (minimum ? point_[j] - box_[j].lower() : box_[j].upper() - point_[j]) / w;
        if (gap < best_gap) best_gap = gap, best = {j, minimum};
      }
    return best;
  }

 private:
  LpSolver& solver_;
  std::span<const int> columns_;
  Box& box_;
  long& lps_solved_;
  std::vector<char> reached_;  // per column: lower bound (2j) and upper bound (2j + 1) done
  std::vector<double> point_;
};

}  // namespace

bool tighten_columns(LpSolver& solver, std::span<const int> columns, Box& box, long& lps_solved,
                     const std::function<bool()>* stop, Order order) {
  Pass pass(solver, columns, box, lps_solved);
  if (order == Order::nearest_bound) {
    for (auto [var, minimum] = pass.nearest_open(); var >= 0; std::tie(var, minimum) = pass.nearest_open()) {
      if (stop && (*stop)()) break;
      if (!pass.tighten(var, minimum)) return false;
    }
    return true;
  }
  for (int var : columns) {
    if (stop && (*stop)()) break;
    for (bool minimum : {true, false})
      if (pass.open(var, minimum) && !pass.tighten(var, minimum)) return false;
  }
  return true;
}

}  // namespace linkbox::prune::lp
