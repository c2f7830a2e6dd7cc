#include "solve/share.hpp"

#include "solve/subproblem.hpp"

namespace linkbox::solve {

void Piece::merge(Piece&& o) {
  for (auto& n : o.state.pending) state.pending.push_back(std::move(n));
  for (auto& f : o.state.solutions) state.solutions.push_back(std::move(f));
  state.stats += o.state.stats;
  state.work += o.state.work;
  state.volume_done += o.state.volume_done;
  if (counters.empty()) counters.resize(o.counters.size());
  for (size_t k = 0; k < o.counters.size() && k < counters.size(); ++k) counters[k] += o.counters[k];
  if (race.empty()) race = std::move(o.race);
  if (race_choices.empty()) race_choices = std::move(o.race_choices);
  if (strategy.empty()) strategy = std::move(o.strategy);
}

bool run_subproblem(const formulate::Formulation& formulation, size_t i, const RunOptions& options, Budget& budget,
                    Sharing* sharing, SubResult& s, Piece& piece) {
  const formulate::SubProblem sub = formulation.subproblem(i);
  describe(sub, i, s);
  Checkpointer none;
  Shared shared{options, budget, none, options.threads, sharing};
  Tally tally;
  return solve_subproblem(formulation, i, sub, nullptr, shared, tally, s, &piece);
}

namespace {

// A search of sub-problem i with a strategy another process chose, over `state`'s boxes.
struct Resumed {
  Resumed(const formulate::Formulation& formulation, size_t i, const RunOptions& options, Budget& budget,
          const Strategy& strategy, SearchState state)
      : sub(formulation.subproblem(i)),
        settings(settings_for(options, sub)),
        bisector(options.bisect, sub, options.params.sigma),
        ran(make_racer(formulation, i, sub, strategy, settings.strategy)),
        search(sub.system.domain(), *ran->pruning.sequence, sub.split_dims, settings.params, budget, &ran->certifier,
               &bisector) {
    search.set_state(std::move(state));
  }
  formulate::SubProblem sub;
  SubSettings settings;
  Bisector bisector;
  std::unique_ptr<Racer> ran;
  Search search;
};

// Records of a lent subtree go to the lender in batches of this many boxes (a few hundred
// kilobytes of JSON), so that they are there when its front gets to them.
constexpr size_t kRecordBatch = 512;

}  // namespace

Piece run_subtree(const formulate::Formulation& formulation, size_t i, const RunOptions& options, Budget& budget,
                  Sharing* sharing, const Strategy& strategy, std::vector<SearchState::Node> nodes, bool record) {
  SearchState start;
  start.pending = std::move(nodes);
  Resumed r(formulation, i, options, budget, strategy, std::move(start));
  if (record) r.search.record_boxes();
  Search& search = r.search;
  if (sharing)
    search.pause_when([sharing, &search, record] {
      return sharing->asked() || sharing->abandoned() || (record && search.recorded() >= kRecordBatch);
    });
  while (!search.run(options.threads)) {
    if (!search.paused()) continue;
    if (sharing->abandoned()) break;
    if (record && search.recorded() >= kRecordBatch) sharing->send_records(i, search.take_records());
    if (sharing->asked()) sharing->give(i, strategy, search);
  }
  return {i, strategy, r.search.state(), r.ran->pruning.sequence->counters(), {}, {}};
}

SubResult finish_subproblem(const formulate::Formulation& formulation, size_t i, const RunOptions& options,
                            Budget& budget, Piece merged) {
  Resumed r(formulation, i, options, budget, merged.strategy, std::move(merged.state));
  r.ran->pruning.sequence->set_counters(merged.counters);
  SubResult s;
  describe(r.sub, i, s);
  s.bisect = to_string(r.bisector.rule());
  s.race = std::move(merged.race);
  s.race_choices = std::move(merged.race_choices);
  const double work = r.search.work();
  finish(r.sub, r.settings, budget, *r.ran, r.bisector, r.search.result(), work, s);
  return s;
}

SubResult unstarted_subproblem(const formulate::Formulation& formulation, size_t i) {
  const formulate::SubProblem sub = formulation.subproblem(i);
  SubResult s;
  describe(sub, i, s);
  s.complete = false;
  s.volume_left = 1;
  s.pending = {sub.system.domain()};
  return s;
}

}  // namespace linkbox::solve
