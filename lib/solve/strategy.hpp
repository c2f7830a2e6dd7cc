#pragma once
// Builds the contractor chain named on the command line (e.g. "trapezoid") for a
// sub-problem. New strategies register here and nowhere else.
#include "formulate/formulation.hpp"
#include "prune/contractor.hpp"
#include "prune/lp/lp_solver.hpp"

#include <string>
#include <vector>

namespace linkbox::solve {

struct StrategyOptions {
  std::vector<std::string> contractors{"trapezoid"};
  prune::lp::LpBackend lp = prune::lp::LpBackend::safe;  // safe | exact (float follows from arith)
  Arith arith = Arith::verified;
};

// Throws std::invalid_argument for an unknown name or a strategy that does not apply to
// the sub-problem (e.g. trapezoid on a system that is not multi-affine).
std::unique_ptr<prune::Sequence> make_strategy(const StrategyOptions& options, const formulate::SubProblem& sub);

std::vector<std::string> parse_strategy_list(const std::string& text);  // "hc4,lp" -> {"hc4","lp"}
std::string strategy_name(const std::vector<std::string>& contractors);  // {"hc4","lp"} -> "hc4,lp"

}  // namespace linkbox::solve
