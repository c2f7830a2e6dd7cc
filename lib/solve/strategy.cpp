#include "solve/strategy.hpp"

#include "formulate/to_lph.hpp"
#include "prune/acid.hpp"
#include "prune/hc4.hpp"
#include "prune/lifted.hpp"
#include "prune/lp_relaxation.hpp"
#include "prune/newton_contractor.hpp"
#include "prune/trapezoid.hpp"

#include <algorithm>
#include <stdexcept>

namespace linkbox::solve {

using namespace prune;

namespace {

std::unique_ptr<Contractor> make_contractor(const std::string& name, const StrategyOptions& options,
                                            const formulate::SubProblem& sub) {
  const model::System& pruned = sub.pruned();
  if (name == "trapezoid") {
    if (!pruned.is_multi_affine())
      throw std::invalid_argument("--prune trapezoid needs a multi-affine system; this one is not");
    return std::make_unique<Trapezoid>(pruned.equations, options.arith);
  }
  if (name == "lp") {
    const auto backend = options.arith != Arith::verified ? lp::LpBackend::float_trusted : options.lp;
    if (sub.lph) return std::make_unique<LpRelaxation>(*sub.lph, backend);
    // Any polynomial system, lifted to L/P/H form around the search's own variables.
    model::LphSystem lph = formulate::to_lph(sub.system);
    auto inner = std::make_unique<LpRelaxation>(lph, backend);
    return std::make_unique<Lifted>(std::move(lph), sub.system.variables.size(), std::move(inner));
  }
  if (name == "newton") return std::make_unique<IntervalNewton>(pruned.equations, pruned.variables.size(), options.arith);
  if (name == "hc4") return std::make_unique<Hc4>(pruned.equations, options.arith, pruned.inequalities);
  if (name == "acid") {
    std::vector<int> dims;
    for (int d : sub.split_dims)
      if (d < static_cast<int>(pruned.variables.size())) dims.push_back(d);
    return std::make_unique<Acid>(std::make_unique<Hc4>(pruned.equations, options.arith, pruned.inequalities), dims);
  }
  throw std::invalid_argument("unknown pruning strategy '" + name + "' (known: auto, trapezoid, lp, hc4, acid, newton)");
}

}  // namespace

std::vector<std::vector<std::string>> auto_candidates(const formulate::SubProblem& sub) {
  if (sub.clipping && sub.pruned().is_multi_affine()) return {{"trapezoid"}};
  return {{"hc4", "newton"}, {"hc4", "newton", "/", "lp"}};
}

Strategy make_strategy(const StrategyOptions& options, const formulate::SubProblem& sub) {
  Strategy s;
  for (auto& name : options.contractors) {
    if (name == "auto") {
      const auto chosen = auto_candidates(sub).front();
      s.names.insert(s.names.end(), chosen.begin(), chosen.end());
    } else {
      s.names.push_back(name);
    }
  }
  std::vector<std::unique_ptr<Contractor>> members;
  std::vector<int> stages;
  int stage = 0;
  for (auto& name : s.names) {
    if (name == "/") {
      stage += !members.empty() && stages.back() == stage;
      continue;
    }
    members.push_back(make_contractor(name, options, sub));
    stages.push_back(stage);
  }
  if (members.empty()) throw std::invalid_argument("no pruning strategy given");
  s.sequence = std::make_unique<Sequence>(std::move(members), sub.split_dims, std::move(stages), options.stall);
  return s;
}

std::vector<std::string> parse_strategy_list(const std::string& text) {
  std::vector<std::string> r;
  std::string item;
  auto flush = [&] {
    if (!item.empty()) r.push_back(item);
    item.clear();
  };
  for (char c : text) {
    if (c == ',' || c == '/') {
      flush();
      if (c == '/') r.push_back("/");
    } else if (c != ' ') {
      item += c;
    }
  }
  flush();
  // Checked here so a misspelt name fails before any work, wherever it was written.
  for (auto& name : r)
    if (name != "/" && name != "auto" && name != "trapezoid" && name != "lp" && name != "hc4" && name != "acid" &&
        name != "newton")
      throw std::invalid_argument("unknown pruning strategy '" + name + "' (known: auto, trapezoid, lp, hc4, acid, newton)");
  if (std::count(r.begin(), r.end(), "/") == static_cast<long>(r.size()))
    throw std::invalid_argument("no pruning strategy given");
  return r;
}

std::string strategy_name(const std::vector<std::string>& contractors) {
  std::string n;
  for (size_t i = 0; i < contractors.size(); ++i) {
    const bool stage = contractors[i] == "/";
    n += stage ? "/" : (i == 0 || contractors[i - 1] == "/" ? "" : ",") + contractors[i];
  }
  return n;
}

}  // namespace linkbox::solve
