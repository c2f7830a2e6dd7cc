#pragma once
// Builds the contractor chain named on the command line (e.g. "trapezoid") for a
// sub-problem. New strategies register here and nowhere else.
#include "formulate/formulation.hpp"
#include "prune/contractor.hpp"

#include <string>
#include <vector>

namespace linkbox::prune {

struct StrategyOptions {
  std::vector<std::string> contractors{"trapezoid"};
  std::string lp = "safe";  // safe | exact
  bool rigorous = true;     // false: --arith float, the unverified variant
};

// Throws std::invalid_argument for an unknown name or a strategy that does not apply to
// the sub-problem (e.g. trapezoid on a system that is not multi-affine).
std::unique_ptr<Sequence> make_strategy(const StrategyOptions& options, const formulate::SubProblem& sub);

std::vector<std::string> parse_strategy_list(const std::string& text);  // "hc4,lp" -> {"hc4","lp"}

}  // namespace linkbox::prune
