#pragma once
// Builds the contractor chain named on the command line for a sub-problem. New strategies
// register here and nowhere else. A name list is comma-separated; '/' starts a stage that
// runs only when the stages before it stall ("hc4,newton/lp": the LP relaxation only where
// propagation and Newton no longer shrink the box). "auto" chooses from the system's shape.
#include "formulate/formulation.hpp"
#include "prune/lp/lp_solver.hpp"
#include "prune/sequence.hpp"

#include <string>
#include <vector>

namespace linkbox::solve {

struct StrategyOptions {
  std::vector<std::string> contractors{"auto"};  // names; "/" separates stages
  prune::lp::LpBackend lp = prune::lp::LpBackend::safe;  // safe | exact (float follows from arith)
  Arith arith = Arith::verified;
  double stall = 0.99;  // a stage stalls when it keeps more than this of the volume
};

struct Strategy {
  std::unique_ptr<prune::Sequence> sequence;
  std::vector<std::string> names;  // what runs, "auto" resolved, "/" between stages
};

// What "auto" chooses from on a sub-problem: trapezoid clipping on the spherical paper's
// formulation; otherwise propagation and Newton alone, or with the LP relaxation where
// they stall. The LP relaxation cuts the box count by 30-30 000x, but an LP costs as much as
// kLpWork boxes, so which one wins depends on the system: solve_case races them.
std::vector<std::vector<std::string>> auto_candidates(const formulate::SubProblem& sub);

// Throws std::invalid_argument for an unknown name or a strategy that does not apply to
// the sub-problem (e.g. trapezoid on a system that is not multi-affine).
Strategy make_strategy(const StrategyOptions& options, const formulate::SubProblem& sub);

// "hc4,newton/lp" -> {"hc4","newton","/","lp"}; std::invalid_argument for an unknown name.
std::vector<std::string> parse_strategy_list(const std::string& text);
std::string strategy_name(const std::vector<std::string>& contractors);  // the reverse

}  // namespace linkbox::solve
