#pragma once
// A strategy's contractors built for one sub-problem, from strategy.cpp's table of
// contractors (new contractors register there and nowhere else).
#include "formulate/formulation.hpp"
#include "interval/interval.hpp"
#include "prune/sequence.hpp"
#include "prune/lp/lp_solver.hpp"
#include "prune/lp/tighten.hpp"
#include "solve/strategy.hpp"

#include <memory>
#include <vector>

namespace linkbox::solve {

struct StrategyOptions {
  Strategy prune = Strategy::automatic();
  prune::lp::LpBackend lp = prune::lp::LpBackend::safe;  // safe | exact (float follows from arith)
  prune::lp::Order lp_order = prune::lp::Order::nearest_bound;  // the lp contractor's
  Arith arith = Arith::verified;
  double stall = 0.99;  // a stage stalls when it keeps more than this of the volume
};

// What a strategy runs on `sub`: itself, or for "auto" its candidates: trapezoid clipping on
// the spherical paper's formulation; otherwise propagation and Newton alone, or with the LP
// relaxation where they stall. The LP relaxation cuts the box count by orders of magnitude,
// but an LP costs as much as many boxes, how many depending on the system, so which one wins
// depends on the system too (papers/decisions/solve-driver.md): solve/race.hpp races them.
std::vector<Strategy> candidates(const Strategy& strategy, const formulate::SubProblem& sub);

struct Pruning {
  Strategy strategy;  // what runs ("auto" resolved)
  std::unique_ptr<prune::Sequence> sequence;
};

// `strategy` is not "auto" (see candidates). Throws std::invalid_argument for a strategy that
// does not apply to the sub-problem (e.g. trapezoid on a system that is not multi-affine).
Pruning make_pruning(const Strategy& strategy, const StrategyOptions& options, const formulate::SubProblem& sub);

}  // namespace linkbox::solve
