#pragma once
// What a search returns: solution boxes per sub-problem, counts, and whether it covered the
// whole domain. Plain data, read by verify and report.
#include "interval/box.hpp"
#include "prune/counters.hpp"
#include "solve/strategy.hpp"

#include <string>
#include <vector>

namespace linkbox::solve {

struct Stats {
  long processed = 0;  // boxes taken from the list
  long empty = 0;
  long solution = 0;
  long split = 0;
  long shrinks = 0;    // contractor passes
  long certified = 0;  // solution boxes certified during the search (a subset of `solution`)
  long certify_calls = 0;
  double seconds = 0;
  Stats& operator+=(const Stats& o);
};

struct SubResult {
  size_t index = 0;
  std::string label;
  int equations = 0;
  int variables = 0;
  std::vector<Box> solutions;  // in the sub-problem's search variables
  // Per solution: a rigorous upper bound on max_i |f_i| at its midpoint, f the sub-problem's
  // equations (model::residual_bound).
  std::vector<double> residuals;
  // Per solution: certified during the search (exactly one root of the case in it, proved in
  // the natural system); refined no further.
  std::vector<char> certified;
  Stats stats;
  bool complete = true;
  // When incomplete: the boxes not yet explored (search variables) and the share of the
  // domain's volume (split dimensions) they hold.
  std::vector<Box> pending;
  double volume_left = 0;
  // Solution boxes of a complete search due for another round of refinement or narrowing
  // (refine.hpp, narrow.hpp) that a limit left as they were.
  long unrefined = 0;
  std::vector<prune::Counters> counters;  // per contractor of the strategy
  // Per contractor of narrowing_strategy() when the boxes were narrowed (narrow.hpp), else empty.
  std::vector<prune::Counters> narrow_counters;
  Strategy strategy;                      // what ran ("auto" resolved; none when no search did)
  std::string bisect;                     // the bisection rule ("auto" resolved)
  double rho = 0;                         // the rho used (auto resolved)
  // When "auto" raced candidates: each one's name and work done (in boxes of propagation,
  // search.hpp), the winner last.
  std::vector<std::pair<std::string, double>> race;
  std::vector<std::string> race_choices;  // and why the lead went where it did, turn by turn
};

struct CaseResult {
  std::vector<SubResult> subproblems;
  Strategy strategy;                          // what ran (see SubResult::strategy)
  std::string bisect;                         // likewise
  double rho = 0;                             // likewise
  std::vector<std::string> contractor_names;  // one per counter
  Stats total;
  std::vector<prune::Counters> counters;  // summed over sub-problems
  bool complete = true;
  std::string stop_reason;  // why incomplete: "time limit reached", "CPU time limit reached", "box limit reached", "interrupted"
  long pending_boxes = 0;   // unexplored boxes over all sub-problems
  long unrefined = 0;       // over all sub-problems (SubResult::unrefined)
  std::string refine_stop;  // when unrefined > 0: the limit that stopped the refinement
  long boxes_taken = 0;     // boxes processed, raced candidates' included: the progress lines' count
  double volume_left = 0;   // unexplored share of the domain, averaged over sub-problems
  bool rigorous = true;     // false: float pruning (--arith float), exclusion not proved
  double seconds = 0;       // wall clock of the whole run
  double cpu_seconds = 0;   // CPU time of the process during the run (user + system, every thread)
};

}  // namespace linkbox::solve
