#pragma once
// The whole run's figures from its sub-problems, as solve_case (and a distributed run) ends.
#include "solve/search.hpp"
#include "solve/result.hpp"
#include "solve/solve_case.hpp"

namespace linkbox::solve {

// Totals, counters by contractor, the strategy that ran, completeness; `result.subproblems` filled.
void summarise(CaseResult& result, const RunOptions& options, const Budget& budget);

}  // namespace linkbox::solve
