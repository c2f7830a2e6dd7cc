#pragma once
// One sub-problem's search, as solve_case runs it and the steps of share.hpp hand it out: its
// settings, its race (one candidate or "auto"'s several), pauses for checkpoints and for
// boxes asked by other processes, and its result (refined when complete).
#include "formulate/formulation.hpp"
#include "solve/bisector.hpp"
#include "solve/checkpoint.hpp"
#include "solve/progress.hpp"
#include "solve/race.hpp"
#include "solve/share.hpp"
#include "solve/solve_case.hpp"

namespace linkbox::solve {

// The settings a search of `sub` runs with. The user's rho (0: not given) is resolved here, and
// only here, into the two thresholds it sets: a box is split when a pass keeps more than
// params.rho of its volume (rho_for the formulation), and a later stage of the strategy runs
// when the earlier ones keep more than strategy.stall (the papers' rule on every formulation).
struct SubSettings {
  Params params;
  StrategyOptions strategy;
};
SubSettings settings_for(const RunOptions& options, const formulate::SubProblem& sub);

// What a sub-problem run needs from the whole run.
struct Shared {
  const RunOptions& options;
  Budget& budget;
  Checkpointer& checkpoints;
  int threads;  // inside the sub-problem
  Sharing* sharing = nullptr;
};

// The result's description of sub-problem i: index, label, size.
void describe(const formulate::SubProblem& sub, size_t i, SubResult& s);

// A sub-problem's result from its search's (or merged searches') result `r`, which took `work`:
// refined when complete and Newton can certify, narrowed when asked (narrow.hpp), residuals,
// the strategy's counters.
void finish(const formulate::SubProblem& sub, const SubSettings& settings, Budget& budget, Racer& ran,
            const Bisector& bisector, Result r, double work, SubResult& s);

// Searches sub-problem i from its start, or from `resume`. Returns false (and fills `piece`)
// when `run.sharing` took some of its boxes: see share.hpp.
bool solve_subproblem(const formulate::Formulation& formulation, size_t i, const formulate::SubProblem& sub,
                      const SubCheckpoint* resume, Shared& run, Tally& tally, SubResult& s, Piece* piece);

}  // namespace linkbox::solve
