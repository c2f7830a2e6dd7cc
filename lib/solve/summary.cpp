#include "solve/summary.hpp"

#include <algorithm>

namespace linkbox::solve {

namespace {

// Adds `counters` (when given) under `name`, listing the name in any case.
void add_named(CaseResult& result, const std::string& name, const prune::Counters* counters) {
  auto at = std::find(result.contractor_names.begin(), result.contractor_names.end(), name);
  if (at == result.contractor_names.end()) {
    result.contractor_names.push_back(name);
    result.counters.emplace_back();
    at = result.contractor_names.end() - 1;
  }
  if (counters) result.counters[at - result.contractor_names.begin()] += *counters;
}

// By name: sub-problems may have run different strategies ("auto" chooses per sub-problem),
// and the narrowing its own. A system with links ran the "links" contractor before the
// strategy's (make_pruning): one member more than the strategy names.
void add_counters(CaseResult& result, const Strategy& strategy, const std::vector<prune::Counters>& counters) {
  size_t members = 0;
  for (auto& stage : strategy.stages()) members += stage.size();
  size_t k = 0;
  if (counters.size() == members + 1) add_named(result, "links", &counters[k++]);
  for (auto& stage : strategy.stages())
    for (ContractorKind kind : stage) {
      add_named(result, name_of(kind), k < counters.size() ? &counters[k] : nullptr);
      ++k;
    }
}

}  // namespace

void summarise(CaseResult& result, const RunOptions& options, const Budget& budget) {
  const size_t n = result.subproblems.size();
  for (auto& s : result.subproblems) {
    result.total += s.stats;
    result.complete = result.complete && s.complete;
    result.pending_boxes += static_cast<long>(s.pending.size());
    result.unrefined += s.unrefined;
    result.volume_left += s.volume_left / static_cast<double>(n);
    add_counters(result, s.strategy, s.counters);
    if (!s.narrow_counters.empty()) add_counters(result, narrowing_strategy(), s.narrow_counters);
  }
  // What ran: the first sub-problem's strategy ("auto" resolved).
  for (auto& s : result.subproblems)
    if (!s.strategy.empty()) {
      result.strategy = s.strategy;
      result.bisect = s.bisect;
      result.rho = s.rho;
      break;
    }
  result.rigorous = options.strategy.arith == Arith::verified;
  if (!result.complete) result.stop_reason = budget.reason();
  if (result.unrefined) result.refine_stop = budget.reason().empty() ? "a limit reached" : budget.reason();
  result.seconds = budget.elapsed();
  result.boxes_taken = budget.boxes_taken();
}

}  // namespace linkbox::solve
