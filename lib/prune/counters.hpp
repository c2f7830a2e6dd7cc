#pragma once
// What a contractor did during a run: plain data, read by solve's results and the reports.
namespace linkbox::prune {

// How the exact LP backend reached its answers (prune/lp/exact_lp.hpp); zero elsewhere.
struct LpPaths {
  long basis = 0;     // CLP's optimal basis, checked primal and dual feasible in rationals
  long repaired = 0;  // the same after exact simplex pivots from CLP's basis
  long farkas = 0;    // infeasible: float multipliers checked as a Farkas certificate in rationals
  long fallback = 0;  // CGAL's exact QP solver from scratch
  long pivots = 0;    // exact pivots over all repairs

  LpPaths& operator+=(const LpPaths& o);
  LpPaths& operator-=(const LpPaths& o);
  bool any() const { return basis || repaired || farkas || fallback || pivots; }
};

struct Counters {
  long calls = 0;
  long emptied = 0;
  double seconds = 0;
  double volume_removed = 0;  // sum over calls of (1 - volume ratio) on the split dimensions
  long lps_solved = 0;        // LP-based contractors: LPs solved (a min or a max each)
  long lp_iterations = 0;     // and the simplex iterations they took
  // The work done, counted from the system's structure and the LPs' sizes and pivots in one
  // unit (about one interval multiply-add), so that contractors of different kinds compare.
  // Every count added is a multiple of 1/4, so sums stay exact in double (below 2^51): a
  // box's share of the work is the same on whichever thread's clone ran it.
  double operations = 0;
  LpPaths lp_paths;

  Counters& operator+=(const Counters& o);
};

}  // namespace linkbox::prune
