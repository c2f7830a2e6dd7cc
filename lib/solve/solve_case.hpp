#pragma once
// Runs branch-and-prune over every sub-problem of a formulation (threads across
// sub-problems; results are stored by sub-problem index, so output does not depend on
// scheduling), with shared limits and progress on stderr.
#include "formulate/formulation.hpp"
#include "prune/strategy.hpp"
#include "solve/branch_and_prune.hpp"

namespace linkbox::solve {

struct SubResult {
  size_t index = 0;
  std::string label;
  int equations = 0;
  int variables = 0;
  std::vector<Box> solutions;  // in the sub-problem's search variables
  Stats stats;
  bool complete = true;
  std::vector<prune::Counters> counters;  // per contractor of the strategy
};

struct CaseResult {
  std::vector<SubResult> subproblems;
  std::vector<std::string> contractor_names;
  Stats total;
  std::vector<prune::Counters> counters;  // summed over sub-problems
  bool complete = true;
  std::string stop_reason;  // why incomplete
  bool rigorous = true;     // false: float pruning (--arith float), exclusion not proved
  double seconds = 0;       // wall clock of the whole run
};

struct RunOptions {
  Params params;
  prune::StrategyOptions strategy;
  int threads = 1;
  bool progress = true;  // progress lines on stderr for runs over a second
};

CaseResult solve_case(const formulate::Formulation& formulation, const RunOptions& options);

}  // namespace linkbox::solve
