#pragma once
// The sub-problem search of solve_case, cut into the steps a driver that spreads one run over
// several processes (distributed/) hands out: a whole sub-problem, a subtree of one (pending
// boxes another search gave away, with their places in the tree and their LP backoff), and the
// finish of a sub-problem from the pieces its searches left. Every box is processed as one
// process would, so the merged pieces end as the unbroken search does.
#include "solve/lending.hpp"
#include "solve/search_state.hpp"
#include "solve/solve_case.hpp"
#include "solve/strategy.hpp"
#include "solve/summary.hpp"  // summarise: a distributed run ends as solve_case does

#include <string>
#include <utility>
#include <vector>

namespace linkbox::solve {

// What one process's search of a sub-problem (or of a subtree of it) left: solution boxes with
// their paths, counts and work, and the boxes still pending when a limit stopped it.
struct Piece {
  size_t subproblem = 0;
  Strategy strategy;  // the candidate that ran ("auto" resolved; after a race its winner)
  SearchState state;
  std::vector<prune::Counters> counters;
  std::vector<std::pair<std::string, double>> race;  // as SubResult::race (the whole sub-problem's)
  std::vector<std::string> race_choices;             // as SubResult::race_choices
  // Adds another piece of the same sub-problem and strategy: solutions, counts, work, pending.
  void merge(Piece&& other);
};

// Runs sub-problem i as solve_case does (its race when "auto" has several candidates).
// Returns true with `s` filled when it ended here (finished, or stopped by a limit before any of
// its boxes went elsewhere); false with `piece` filled when some boxes were given away: the
// sub-problem is finished (finish_subproblem) once every piece is back.
bool run_subproblem(const formulate::Formulation& formulation, size_t i, const RunOptions& options, Budget& budget,
                    Sharing* sharing, SubResult& s, Piece& piece);

// Searches pending boxes of sub-problem i (a subtree given away, or lent: `record` keeps a
// record of every box, for the lender) with `strategy`.
Piece run_subtree(const formulate::Formulation& formulation, size_t i, const RunOptions& options, Budget& budget,
                  Sharing* sharing, const Strategy& strategy, std::vector<SearchState::Node> nodes,
                  bool record = false);

// Sub-problem i's result from all its pieces merged, as the single search would have ended it:
// solutions in search-tree order, refinement when complete, residuals.
SubResult finish_subproblem(const formulate::Formulation& formulation, size_t i, const RunOptions& options,
                            Budget& budget, Piece merged);

// A sub-problem that no search reached before a limit stopped the run.
SubResult unstarted_subproblem(const formulate::Formulation& formulation, size_t i);

}  // namespace linkbox::solve
