#include "solve/strategy.hpp"

#include "formulate/to_lph.hpp"
#include "prune/hc4.hpp"
#include "prune/lifted.hpp"
#include "prune/lp_relaxation.hpp"
#include "prune/newton_contractor.hpp"
#include "prune/trapezoid.hpp"

#include <sstream>
#include <stdexcept>

namespace linkbox::solve {

using namespace prune;

std::unique_ptr<Sequence> make_strategy(const StrategyOptions& options, const formulate::SubProblem& sub) {
  std::vector<std::unique_ptr<Contractor>> members;
  for (auto& name : options.contractors) {
    if (name == "trapezoid") {
      if (!sub.system.is_multi_affine())
        throw std::invalid_argument("--prune trapezoid needs a multi-affine system; this one is not");
      members.push_back(std::make_unique<Trapezoid>(sub.system.equations, options.arith));
    } else if (name == "lp") {
      const auto backend = options.arith != Arith::verified ? lp::LpBackend::float_trusted : options.lp;
      if (sub.lph) {
        members.push_back(std::make_unique<LpRelaxation>(*sub.lph, backend));
      } else {
        // Any polynomial system, lifted to L/P/H form around the search's own variables.
        model::LphSystem lph = formulate::to_lph(sub.system);
        auto inner = std::make_unique<LpRelaxation>(lph, backend);
        members.push_back(std::make_unique<Lifted>(std::move(lph), sub.system.variables.size(), std::move(inner)));
      }
    } else if (name == "newton") {
      members.push_back(std::make_unique<IntervalNewton>(sub.system.equations, sub.system.variables.size(), options.arith));
    } else if (name == "hc4") {
      members.push_back(std::make_unique<Hc4>(sub.system.equations, options.arith));
    } else {
      throw std::invalid_argument("unknown pruning strategy '" + name + "'");
    }
  }
  if (members.empty()) throw std::invalid_argument("no pruning strategy given");
  return std::make_unique<Sequence>(std::move(members), sub.split_dims);
}

std::vector<std::string> parse_strategy_list(const std::string& text) {
  std::vector<std::string> r;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) r.push_back(item);
  return r;
}

std::string strategy_name(const std::vector<std::string>& contractors) {
  std::string n;
  for (auto& c : contractors) n += (n.empty() ? "" : ",") + c;
  return n;
}

}  // namespace linkbox::solve
