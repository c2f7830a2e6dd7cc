#pragma once
// Runs branch-and-prune over every sub-problem of a formulation (threads across
// sub-problems; results are stored by sub-problem index, so output does not depend on
// scheduling), with shared limits and progress on stderr.
#include "formulate/formulation.hpp"
#include "solve/bisector.hpp"
#include "solve/result.hpp"
#include "solve/pruning.hpp"
#include "solve/search.hpp"

#include <map>
#include <string>

namespace linkbox::solve {

struct Checkpoint;

struct RunOptions {
  Params params;
  StrategyOptions strategy;
  Bisect bisect = Bisect::automatic;
  int threads = 1;
  bool progress = true;  // progress lines on stderr for runs over a second
  // Checkpoints (solve/checkpoint.hpp): written to `checkpoint` (when not empty) every
  // `checkpoint_every` seconds and when the run ends. `checkpoint_header` is a JSON object's
  // text saying what the run is (its case and settings), compared when resuming.
  std::string checkpoint;
  BoxLog* box_log = nullptr;  // every processed box, when set (`--record-tree`)
  double checkpoint_every = 60;
  std::string checkpoint_header = "{}";
  const Checkpoint* resume = nullptr;  // go on from this state (its settings must be these)
  // Where each setting came from, for the report: name -> "case file" or "flag" (absent: default).
  std::map<std::string, std::string> setting_source;
};

CaseResult solve_case(const formulate::Formulation& formulation, const RunOptions& options);

}  // namespace linkbox::solve
