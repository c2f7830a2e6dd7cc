#pragma once
// Runs branch-and-prune over every sub-problem of a formulation (threads across
// sub-problems; results are stored by sub-problem index, so output does not depend on
// scheduling), with shared limits and progress on stderr.
#include "formulate/formulation.hpp"
#include "solve/bisector.hpp"
#include "solve/branch_and_prune.hpp"
#include "solve/result.hpp"
#include "solve/strategy.hpp"

namespace linkbox::solve {

struct RunOptions {
  Params params;
  StrategyOptions strategy;
  Bisect bisect = Bisect::automatic;
  int threads = 1;
  bool progress = true;  // progress lines on stderr for runs over a second
};

CaseResult solve_case(const formulate::Formulation& formulation, const RunOptions& options);

}  // namespace linkbox::solve
