#include "solve/subproblem.hpp"

#include "solve/narrow.hpp"
#include "solve/refine.hpp"

#include <algorithm>

namespace linkbox::solve {

SubSettings settings_for(const RunOptions& options, const formulate::SubProblem& sub) {
  SubSettings s{options.params, options.strategy};
  s.params.rho = rho_for(options.params.rho, sub.clipping);
  s.strategy.stall = rho_for(options.params.rho, true);  // the LP stage waits for a stall as in the paper
  return s;
}

void describe(const formulate::SubProblem& sub, size_t i, SubResult& s) {
  s.index = i;
  s.label = sub.label;
  s.equations = static_cast<int>(sub.system.equations.size() + sub.system.links.size());  // a link is one
  s.variables = static_cast<int>(sub.system.variables.size());
}

void finish(const formulate::SubProblem& sub, const SubSettings& settings, Budget& budget, Racer& ran,
            const Bisector& bisector, Result r, double work, SubResult& s) {
  const Params& params = settings.params;
  s.strategy = ran.pruning.strategy;
  s.complete = r.complete;
  s.rho = params.rho;
  // Only Newton tells the certifier where to look; without it a refinement cannot certify.
  if (r.complete && ran.pruning.strategy.uses(ContractorKind::newton))
    s.unrefined = refine(r, work, sub, params, budget, *ran.pruning.sequence, ran.certifier, bisector);
  // A refinement that a limit stopped leaves nothing to the narrowing (counting its boxes twice).
  if (r.complete && params.narrow > 0 && s.unrefined == 0) {
    const Pruning fine = make_pruning(narrowing_strategy(), settings.strategy, sub);
    s.unrefined = narrow(r, sub, params, budget, *fine.sequence, bisector);
    auto counters = fine.sequence->counters();
    if (std::any_of(counters.begin(), counters.end(), [](const prune::Counters& c) { return c.calls > 0; }))
      s.narrow_counters = std::move(counters);
  }
  s.solutions = std::move(r.solutions);
  s.certified = std::move(r.certified);
  for (auto& b : s.solutions)
    s.residuals.push_back(std::max(model::residual_bound(sub.system.equations, b),
                                   model::residual_bound(sub.system.links, b)));
  s.stats = r.stats;
  s.pending = std::move(r.pending);
  s.volume_left = r.volume_left;
  s.counters = ran.pruning.sequence->counters();
}

namespace {

// The candidates of sub-problem i, each with its search over the domain.
std::vector<std::unique_ptr<Racer>> start_racers(const formulate::Formulation& formulation, size_t i,
                                                 const formulate::SubProblem& sub, const SubSettings& settings,
                                                 const Bisector& bisector, Shared& run, Tally& tally) {
  std::vector<std::unique_ptr<Racer>> racers;
  for (const Strategy& strategy : candidates(settings.strategy.prune, sub)) {
    auto r = make_racer(formulation, i, sub, strategy, settings.strategy);
    r->search = std::make_unique<Search>(sub.system.domain(), *r->pruning.sequence, sub.split_dims, settings.params,
                                         run.budget, &r->certifier, &bisector);
    r->search->report_to(&tally.pending, &tally.done);
    if (run.options.box_log) r->search->log_to(run.options.box_log, i, static_cast<int>(racers.size()));
    racers.push_back(std::move(r));
  }
  return racers;
}

// Deposits sub-problem i's race with the checkpoint writer, and knows when a new generation
// wants it again.
class Deposit {
 public:
  Deposit(Checkpointer& checkpoints, size_t i, const Race& race) : checkpoints_(checkpoints), i_(i), race_(race) {}
  bool due() const { return checkpoints_.enabled() && checkpoints_.generation() > seen_; }
  void operator()(bool running) {
    if (!checkpoints_.enabled()) return;
    const SubCheckpoint state = race_.checkpoint();
    seen_ = checkpoints_.generation();
    checkpoints_.deposit(i_, state, running);
  }

 private:
  Checkpointer& checkpoints_;
  size_t i_;
  const Race& race_;
  int seen_ = 0;
};

// Runs the race until a candidate wins or a limit stops it. Each step runs one candidate up
// to its target; a pause (a checkpoint, boxes asked for) resumes the same step, so the race
// goes exactly as unbroken. True when `sharing` took some boxes.
bool run_race(Race& race, size_t i, Sharing* sharing, Shared& run, Deposit& deposit) {
  bool gave = false;
  while (!race.over()) {
    Search& search = race.run_turn(run.threads);
    if (race.over() || run.budget.exhausted()) break;
    if (search.paused()) {
      if (sharing && sharing->asked()) gave = sharing->give(i, race.racer(0).pruning.strategy, search) || gave;
      race.lend(i);
      deposit(true);
      continue;
    }
    race.next_turn();
  }
  return gave;
}

}  // namespace

bool solve_subproblem(const formulate::Formulation& formulation, size_t i, const formulate::SubProblem& sub,
                      const SubCheckpoint* resume, Shared& run, Tally& tally, SubResult& s, Piece* piece) {
  const SubSettings settings = settings_for(run.options, sub);
  s.rho = settings.params.rho;
  const Bisector bisector(run.options.bisect, sub, run.options.params.sigma);
  s.bisect = to_string(bisector.rule());
  auto racers = start_racers(formulation, i, sub, settings, bisector, run, tally);
  // A search that does not race gives boxes away; a race's leader lends them (share.hpp).
  Sharing* sharing = racers.size() == 1 ? run.sharing : nullptr;
  Sharing* lending = racers.size() > 1 ? run.sharing : nullptr;
  Race race(std::move(racers), lending, run.options.box_log == nullptr);
  if (resume && resume->phase == SubCheckpoint::Phase::searching) race.resume(i, *resume);
  Deposit deposit(run.checkpoints, i, race);
  if (run.checkpoints.enabled() || sharing || lending)
    for (size_t k = 0; k < race.size(); ++k)
      race.racer(k).search->pause_when([&, k] {
        if (deposit.due()) return true;
        if (sharing) return sharing->asked();
        return race.lend_asked(k);
      });
  deposit(true);

  const bool gave = run_race(race, i, sharing, run, deposit);
  race.end_lending();
  deposit(false);  // after a win too: a checkpoint meanwhile resumes with the refinement
  Racer& ran = race.best();
  s.race = race.record();
  s.race_choices = race.choices();
  if (gave) {
    *piece = {i, ran.pruning.strategy, ran.search->state(), ran.pruning.sequence->counters(), s.race, s.race_choices};
    return false;
  }
  finish(sub, settings, run.budget, ran, bisector, ran.search->result(), ran.search->work(), s);
  // A refinement cut short by a limit is done again on resuming; a whole one is final.
  if (s.complete && !run.budget.exhausted()) {
    SubCheckpoint done;
    done.phase = SubCheckpoint::Phase::finished;
    done.result = s;
    run.checkpoints.deposit(i, done, false);
  }
  return true;
}

}  // namespace linkbox::solve
