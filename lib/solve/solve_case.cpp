#include "solve/solve_case.hpp"

#include "interval/rigorous.hpp"
#include "solve/checkpoint.hpp"
#include "solve/output_file.hpp"
#include "solve/share.hpp"

#include <condition_variable>
#include <exception>
#include <cstdio>
#include <mutex>
#include <algorithm>
#include <map>
#include <thread>

#include <sys/resource.h>

namespace linkbox::solve {

namespace {

// Live figures of one sub-problem, for the progress line.
struct Tally {
  std::atomic<long> pending{0};
  std::atomic<double> done{0};  // share of its volume outside the pending boxes
  std::atomic<bool> finished{false};
};

// Collects each sub-problem's state as it goes and writes the checkpoint. A running search
// deposits its state whenever a new checkpoint generation starts (it pauses between two boxes
// for that); a sub-problem that is not running (not started, refining, finished) keeps its
// last deposit. The file is written once every running one has deposited for the generation,
// by whichever deposits last.
class Checkpointer {
 public:
  Checkpointer(const RunOptions& o, size_t n) : path_(o.checkpoint), every_(o.checkpoint_every), header_(o.checkpoint_header) {
    if (enabled()) slots_.assign(n, {to_json_text(SubCheckpoint{}), 0, false});
  }
  bool enabled() const { return !path_.empty(); }
  int generation() const { return generation_.load(); }
  // running: the state changes and must be deposited again for every new generation.
  void deposit(size_t i, const SubCheckpoint& state, bool running) {
    if (!enabled()) return;
    std::string text = to_json_text(state);
    std::lock_guard lock(m_);
    slots_[i] = {std::move(text), generation_.load(), running};
    write_when_ready();
  }
  void tick(double elapsed) {
    if (!enabled() || elapsed < next_) return;
    next_ = elapsed + every_;
    std::lock_guard lock(m_);
    ++generation_;
    write_when_ready();
  }
  void final_write() {
    if (!enabled()) return;
    std::lock_guard lock(m_);
    write(true);
  }

 private:
  struct Slot {
    std::string text;
    int generation;
    bool running;
  };
  void write_when_ready() {
    if (written_ == generation_.load()) return;
    for (auto& s : slots_)
      if (s.running && s.generation < generation_.load()) return;
    written_ = generation_.load();
    write(false);
  }
  void write(bool last) {
    std::vector<std::string> texts;
    for (auto& s : slots_) texts.push_back(s.text);
    try {
      write_output(path_, checkpoint_text(header_, texts));
    } catch (const std::runtime_error& e) {
      if (last) throw;
      std::fprintf(stderr, "linkbox: checkpoint not written (the run goes on): %s\n", e.what());
    }
  }
  std::string path_;
  double every_;
  std::string header_;
  std::atomic<int> generation_{0};
  int written_ = 0;
  double next_ = 0;
  std::mutex m_;
  std::vector<Slot> slots_;
};

// Once a second: a progress line (runs over a second, when enabled) and the checkpoint clock.
class Ticker {
 public:
  Ticker(bool progress, const std::vector<Tally>& tallies, const Budget& budget, Checkpointer& checkpoints)
      : progress_(progress), tallies_(tallies), budget_(budget), checkpoints_(checkpoints) {
    checkpoints_.tick(0);  // the first generation starts at once; the file follows the first deposits
    if (progress_ || checkpoints_.enabled()) thread_ = std::thread([this] { run(); });
  }
  ~Ticker() {
    {
      std::lock_guard lock(m_);
      stop_ = true;
    }
    cv_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

 private:
  void run() {
    std::unique_lock lock(m_);
    while (!cv_.wait_for(lock, std::chrono::seconds(1), [this] { return stop_; })) {
      checkpoints_.tick(budget_.elapsed());
      if (!progress_) continue;
      size_t finished = 0;
      long pending = 0;
      double done = 0;
      for (auto& t : tallies_) {
        const bool f = t.finished.load();
        finished += f;
        pending += f ? 0 : t.pending.load();
        done += f ? 1 : t.done.load();
      }
      // Pending boxes near roots or on a curve hold a sliver of the volume: below what the
      // tally (1 - pending volume) resolves, it reads "<0.001%", never 0 while boxes remain.
      const double left = 100 * std::max(0.0, 1 - done / static_cast<double>(tallies_.size()));
      char volume[32];
      if (pending > 0 && left < 1e-3) std::snprintf(volume, sizeof volume, "<0.001%%");
      else std::snprintf(volume, sizeof volume, "%.3g%%", left);
      std::fprintf(stderr, "linkbox: %zu/%zu sub-problems, %ld boxes, %ld pending, %s of the volume left, %.1f s\n",
                   finished, tallies_.size(), budget_.boxes_taken(), pending, volume, budget_.elapsed());
    }
  }
  bool progress_;
  const std::vector<Tally>& tallies_;
  const Budget& budget_;
  Checkpointer& checkpoints_;
  std::mutex m_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace

namespace {

double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Racer {
  Strategy strategy;
  NaturalCertifier certifier;
  std::unique_ptr<Search> search;
};

// "auto" on a system with several candidates: their searches advance in turns, measured in
// work (boxes + kLpWork per LP), until one finishes; its boxes are the result, as if it had
// run alone. Turns double. After a first turn each, the candidate whose projected total work
// (work / share of the search tree resolved) is smaller gets the turn and the others
// kRaceShare of it, so a wrong projection costs a bounded factor. A turn ends at the box where
// a one-thread depth-first search would end it, whatever the thread count (Search::run), so
// the race is deterministic.
constexpr double kRaceShare = 0.125;
constexpr double kFirstTurn = 4000;

// The projection flatters the LP candidate early on: its first LPs remove whole slabs of the
// box. The lead passes to a costlier candidate only when it is projected this many times
// cheaper than the first.
constexpr double kLeadMargin = 2;

// Progress is the share of the search tree resolved (Search::tree_done), not of the volume:
// contraction removes most of the volume in the first boxes, while the work gathers around
// the solution set, where little volume is left. On volume, a propagation search that had
// cleared all but 1e-5 of a curve's neighbourhood looked nearly done and kept the lead for
// half of the run (bicyclohexane 52 -> 35-40 s CPU, Eco10 29 -> 21 s, mobile 6R 1.14 ->
// 0.97-1.10 s; cyclohexane 0.54-0.60 -> 0.70-0.76 s, where the LP candidate now leads for a while).
double projected(const Search& s) { return s.work() / std::max(s.tree_done(), 1e-9); }

// A solution box that the certifier did not settle (too wide for Newton near a close pair of
// roots, or beside a certified box) is searched again with a smaller sigma, round by round, down to a
// floor: the certified answer should not depend on the user's sigma. What the refinement
// proves empty is dropped, what it certifies replaces the box, what is left stays.
constexpr int kRefineRounds = 4;  // sigma/100 each round, down to the floor
constexpr double kRefineFactor = 1e-2;
constexpr double kSigmaFloor = 1e-12;
constexpr double kRefineWork = 2000;  // per box: what cannot be settled within it is left as it was
// Only small groups of touching uncertified boxes are refined: a close pair of roots leaves a
// few, a curve (a mobile linkage, a singular family) leaves a long chain that no sigma
// resolves, and refining it would only multiply the work.
// A close pair whose Jacobian rows scale with the gap leaves a few hundred sigma-boxes (the
// planted pairs 5e-4 apart: ~120 per root); all the refinements of a run together get at
// most twice the search's work, plus kRefineWork per box for small searches.
constexpr size_t kRefineGroup = 1024;
// Along a curve (a mobile linkage at sigma 0.1) the boxes the curve crosses use up
// kRefineWork each for nothing. So once kRefineProbe of a group's refinements were cut short
// and none certified a root, the rest of the group is left as the search found it. (Giving
// them 50 work each instead dropped the spurious boxes beside the curve, but cost more than
// verifying them: cyclohexane 0.53 -> 0.41 s CPU with 819 boxes left instead of 321, the
// mobile 6R 0.95 -> 0.69 s with 98 instead of 45, bicyclohexane 35.5 -> 33 s. On the 10 000
// planted systems of papers/reliability the same counts are claimed and 4 roots fewer
// certified, of 28 752: close pairs where the 50-work pass certified one after three failed
// probes.)
constexpr int kRefineProbe = 3;
constexpr size_t kRefineMax = 4000;

// Per uncertified solution box: whether its group of touching uncertified boxes is small.
// Per solution: the group of touching uncertified boxes it belongs to, or -1 when it is
// certified or its group is too large to refine.
std::vector<int> small_groups(const Result& r) {
  std::vector<size_t> open;
  for (size_t k = 0; k < r.solutions.size(); ++k)
    if (!r.certified[k]) open.push_back(k);
  std::vector<int> result(r.solutions.size(), -1);
  if (open.size() > kRefineMax) return result;
  std::vector<int> group(open.size(), -1);
  std::vector<size_t> size;
  for (size_t a = 0; a < open.size(); ++a) {
    if (group[a] >= 0) continue;
    const int g = static_cast<int>(size.size());
    size.push_back(0);
    std::vector<size_t> stack{a};
    group[a] = g;
    while (!stack.empty()) {
      const size_t x = stack.back();
      stack.pop_back();
      ++size[g];
      for (size_t b = 0; b < open.size(); ++b)
        if (group[b] < 0 && overlaps(r.solutions[open[x]], r.solutions[open[b]])) {
          group[b] = g;
          stack.push_back(b);
        }
    }
  }
  for (size_t a = 0; a < open.size(); ++a)
    if (size[group[a]] <= kRefineGroup) result[open[a]] = group[a];
  return result;
}

void refine(Result& r, double search_work, const formulate::SubProblem& sub, const Params& params, Budget& budget,
            prune::Sequence& contractor, Certifier& certifier, const Bisector& bisector) {
  Params fine = params;
  double allowance = 2 * search_work + 20 * kRefineWork;
  // A box whose refinement was cut short stays as it was, and a smaller sigma would only
  // make its next attempt costlier: it is not refined again.
  std::vector<char> stuck(r.solutions.size(), 0);
  for (int round = 0; round < kRefineRounds; ++round) {
    fine.sigma = std::max(fine.sigma * kRefineFactor, kSigmaFloor);
    Result out;
    std::vector<char> out_stuck;
    bool changed = false;
    const std::vector<int> group = small_groups(r);
    std::map<int, std::pair<int, int>> tried;  // per group: refinements cut short, roots certified
    for (size_t k = 0; k < r.solutions.size(); ++k) {
      auto& [cut_short, certified] = tried[group[k]];
      const bool curve = cut_short >= kRefineProbe && certified == 0;  // a curve's group, by its probes
      if (r.certified[k] || group[k] < 0 || stuck[k] || curve || budget.exhausted() || fine.sigma >= params.sigma ||
          allowance <= 0) {
        out.solutions.push_back(std::move(r.solutions[k]));
        out.certified.push_back(r.certified[k]);
        out_stuck.push_back(stuck[k] || curve);
        continue;
      }
      Search search(r.solutions[k], contractor, sub.split_dims, fine, budget, &certifier, &bisector);
      const bool finished = search.run(1, std::min(kRefineWork, allowance));
      allowance -= search.work();
      Result part = search.result();
      cut_short += !finished;
      certified += static_cast<int>(std::count(part.certified.begin(), part.certified.end(), 1));
      if (!finished || !part.complete) {  // stopped by a limit: keep the box as it was
        out.solutions.push_back(std::move(r.solutions[k]));
        out.certified.push_back(false);
        out_stuck.push_back(1);
        continue;
      }
      changed = true;
      const double seconds = r.stats.seconds;
      r.stats += part.stats;  // the box was counted as a solution once: its search replaces it
      r.stats.seconds = seconds + part.stats.seconds;
      for (size_t j = 0; j < part.solutions.size(); ++j) {
        out.solutions.push_back(std::move(part.solutions[j]));
        out.certified.push_back(part.certified[j]);
        out_stuck.push_back(0);
      }
    }
    r.solutions = std::move(out.solutions);
    r.certified = std::move(out.certified);
    stuck = std::move(out_stuck);
    if (!changed) break;
  }
  r.stats.solution = static_cast<long>(r.solutions.size());
  r.stats.certified = std::count(r.certified.begin(), r.certified.end(), 1);
}

// What a sub-problem run needs from the whole run.
struct Shared {
  const RunOptions& options;
  Budget& budget;
  Checkpointer& checkpoints;
  int threads;  // inside the sub-problem
  Sharing* sharing = nullptr;
};

std::unique_ptr<Racer> make_racer(const formulate::Formulation& formulation, size_t i, const formulate::SubProblem& sub,
                                  StrategyOptions strategy, const std::vector<std::string>& names) {
  strategy.contractors = names;
  return std::unique_ptr<Racer>(new Racer{make_strategy(strategy, sub), NaturalCertifier(formulation, i), nullptr});
}

StrategyOptions strategy_options(const RunOptions& options) {
  StrategyOptions strategy = options.strategy;
  strategy.stall = rho_for(options.params.rho, true);  // the LP stage waits for a stall as in the paper
  return strategy;
}

// The search settings of one sub-problem: rho resolved (rho_for).
Params params_for(const RunOptions& options, const formulate::SubProblem& sub) {
  Params p = options.params;
  p.rho = rho_for(options.params.rho, sub.clipping);
  return p;
}

// A sub-problem's result from its search's (or merged searches') result: refined when complete
// and Newton can certify, residuals, the strategy's counters.
void finish(const formulate::SubProblem& sub, const Params& params, Budget& budget, Racer& ran,
            const Bisector& bisector, Result r, double work, SubResult& s) {
  s.strategy = ran.strategy.names;
  s.complete = r.complete;
  s.rho = params.rho;
  // Only Newton tells the certifier where to look; without it a refinement cannot certify.
  const auto& names = ran.strategy.names;
  if (r.complete && std::find(names.begin(), names.end(), "newton") != names.end())
    refine(r, work, sub, params, budget, *ran.strategy.sequence, ran.certifier, bisector);
  s.solutions = std::move(r.solutions);
  s.certified = std::move(r.certified);
  for (auto& b : s.solutions) s.residuals.push_back(model::residual_bound(sub.system.equations, b));
  s.stats = r.stats;
  s.pending = std::move(r.pending);
  s.volume_left = r.volume_left;
  s.counters = ran.strategy.sequence->counters();
}

void describe(const formulate::SubProblem& sub, size_t i, SubResult& s) {
  s.index = i;
  s.label = sub.label;
  s.equations = static_cast<int>(sub.system.equations.size());
  s.variables = static_cast<int>(sub.system.variables.size());
}

// Returns false (and fills `piece`) when `run.sharing` took some of its boxes: see share.hpp.
bool solve_subproblem(const formulate::Formulation& formulation, size_t i, const formulate::SubProblem& sub,
                      const SubCheckpoint* resume, Shared& run, Tally& tally, SubResult& s, Piece* piece) {
  const RunOptions& options = run.options;
  const StrategyOptions strategy = strategy_options(options);
  const Params params = params_for(options, sub);
  s.rho = params.rho;
  std::vector<std::vector<std::string>> candidates{strategy.contractors};
  if (strategy.contractors == std::vector<std::string>{"auto"}) candidates = auto_candidates(sub);
  const Bisector bisector(options.bisect, sub, options.params.sigma);
  s.bisect = to_string(bisector.rule());
  std::vector<std::unique_ptr<Racer>> racers;
  for (auto& names : candidates) {
    auto r = make_racer(formulation, i, sub, strategy, names);
    r->search = std::make_unique<Search>(sub.system.domain(), *r->strategy.sequence, sub.split_dims, params,
                                         run.budget, &r->certifier, &bisector);
    r->search->report_to(&tally.pending, &tally.done);
    if (options.box_log) r->search->log_to(options.box_log, i, static_cast<int>(racers.size()));
    racers.push_back(std::move(r));
  }

  RacePosition race{kFirstTurn, 0, 0, -1, -1};
  if (resume && resume->phase == SubCheckpoint::Phase::searching) {
    if (resume->searches.size() != racers.size())
      throw std::invalid_argument("the checkpoint's sub-problem " + std::to_string(i) + " ran " +
                                  std::to_string(resume->searches.size()) + " strategies, this run " +
                                  std::to_string(racers.size()));
    for (size_t k = 0; k < racers.size(); ++k) {
      racers[k]->search->set_state(resume->searches[k]);
      racers[k]->strategy.sequence->set_counters(resume->counters[k]);
    }
    race = resume->race;
  }
  int seen = 0;
  auto save = [&](bool running) {
    if (!run.checkpoints.enabled()) return;
    SubCheckpoint c;
    c.phase = SubCheckpoint::Phase::searching;
    for (auto& r : racers) {
      c.searches.push_back(r->search->state());
      c.counters.push_back(r->strategy.sequence->counters());
    }
    c.race = race;
    seen = run.checkpoints.generation();
    run.checkpoints.deposit(i, c, running);
  };
  // A search that does not race gives boxes away; a race's leader lends them (share.hpp), one
  // candidate only: the first to lend.
  Sharing* sharing = racers.size() == 1 ? run.sharing : nullptr;
  Sharing* lending = racers.size() > 1 ? run.sharing : nullptr;
  int lender = -1;
  // Whichever way this returns (an exception too), no record is delivered to the racers after.
  struct EndLending {
    Sharing* lending;
    ~EndLending() {
      if (lending) lending->end_lending();
    }
  } end_lending{lending};
  bool gave = false;
  if (run.checkpoints.enabled() || sharing || lending)
    for (size_t k = 0; k < racers.size(); ++k)
      racers[k]->search->pause_when([&, k] {
        if (run.checkpoints.enabled() && run.checkpoints.generation() > seen) return true;
        if (sharing) return sharing->asked();
        const bool may_lend = lender < 0 ? k == race.lead && race.turn > kFirstTurn : static_cast<int>(k) == lender;
        return lending && may_lend && lending->asked();
      });
  save(true);

  // The race (one candidate: its search). Each step runs one candidate up to its target; a
  // pause for a checkpoint resumes the same step, so the race goes exactly as unbroken.
  auto pick_lead = [&] {
    race.lead = 0;
    for (size_t k = 1; k < racers.size(); ++k)
      if (projected(*racers[k]->search) * kLeadMargin < projected(*racers[race.lead]->search)) race.lead = k;
  };
  // First turn: every candidate gets the share (a costly first box of one should not delay
  // another that finishes at once: the rigid 6R's LP candidate).
  auto target_of = [&](size_t k) {
    const double share = k == race.lead && race.turn > kFirstTurn ? 1 : kRaceShare;
    return racers[k]->search->work() + race.turn * share;
  };
  while (race.winner < 0) {
    Search& search = *racers[race.next]->search;
    if (racers.size() == 1) {
      search.run(run.threads);
    } else {
      if (race.target < 0) {
        if (race.next == 0 && race.turn > kFirstTurn) pick_lead();
        if (lender >= 0 && race.lead != static_cast<size_t>(lender)) {
          // The lender lost the lead: its lent boxes' searches would serve a likely loser. It
          // takes them back (it may never need them); the new leader lends from now on.
          lending->recall();
          racers[lender]->search->unlend();
          lender = -1;
        }
        race.target = target_of(race.next);
      }
      // Every thread on this candidate's turn: the turn still ends where one thread ends it
      // (look-ahead mode, lookahead.hpp), so the race and its winner do not depend on
      // the thread count.
      search.run(run.threads, race.target);
    }
    if (search.complete()) {
      race.winner = static_cast<int>(race.next);
      break;
    }
    if (run.budget.exhausted()) break;
    if (search.paused()) {
      if (sharing && sharing->asked()) gave = sharing->give(i, racers[0]->strategy.names, search) || gave;
      if (lending && lending->asked() && lending->lend(i, racers[race.next]->strategy.names, search))
        lender = static_cast<int>(race.next);
      save(true);
      continue;
    }
    race.target = -1;  // reached its target: the next candidate's turn
    if (++race.next == racers.size()) {
      race.next = 0;
      race.turn *= 2;
    }
  }

  if (lending) lending->end_lending();
  // The lent boxes' contractors worked for the lender: their counters are its own.
  if (lender >= 0 && race.winner == lender) {
    auto counters = racers[lender]->strategy.sequence->counters();
    const auto delivered = racers[lender]->search->delivered_counters();
    for (size_t k = 0; k < counters.size() && k < delivered.size(); ++k) counters[k] += delivered[k];
    racers[lender]->strategy.sequence->set_counters(std::move(counters));
  }

  // Stopped by a limit: what the most advanced candidate has, and the state to resume from.
  size_t best = 0;
  if (race.winner < 0) {
    save(false);
    for (size_t k = 1; k < racers.size(); ++k)
      if (racers[k]->search->volume_done() > racers[best]->search->volume_done()) best = k;
  } else {
    best = static_cast<size_t>(race.winner);
    save(false);  // a checkpoint meanwhile resumes with the refinement
    for (auto& r : racers)
      if (r.get() != racers[best].get()) s.race.push_back({strategy_name(r->strategy.names), r->search->work()});
    if (racers.size() > 1) s.race.push_back({strategy_name(racers[best]->strategy.names), racers[best]->search->work()});
  }
  Racer& ran = *racers[best];
  if (gave) {
    *piece = {i, ran.strategy.names, ran.search->state(), ran.strategy.sequence->counters(), s.race};
    return false;
  }
  finish(sub, params, run.budget, ran, bisector, ran.search->result(), ran.search->work(), s);
  // A refinement cut short by a limit is done again on resuming; a whole one is final.
  if (s.complete && !run.budget.exhausted()) {
    SubCheckpoint done;
    done.phase = SubCheckpoint::Phase::finished;
    done.result = s;
    run.checkpoints.deposit(i, done, false);
  }
  return true;
}

}  // namespace

CaseResult solve_case(const formulate::Formulation& formulation, const RunOptions& options) {
  const size_t n = formulation.subproblem_count();
  if (options.resume && options.resume->subproblems.size() != n)
    throw std::invalid_argument("the checkpoint has " + std::to_string(options.resume->subproblems.size()) +
                                " sub-problems, this case " + std::to_string(n));
  CaseResult result;
  result.subproblems.resize(n);
  const double cpu_start = process_cpu_seconds();
  Budget budget(options.params);
  Checkpointer checkpoints(options, n);
  std::vector<Tally> tallies(n);
  // Threads go across sub-problems when there are enough of them, else inside each one.
  const int across = std::max(1, std::min<int>(options.threads, static_cast<int>(n)));
  Shared shared{options, budget, checkpoints, n >= static_cast<size_t>(options.threads) ? 1 : options.threads};
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;

  auto worker = [&] {
    for (size_t i; (i = next.fetch_add(1)) < n;) {
      try {
        const SubCheckpoint* resume = options.resume ? &options.resume->subproblems[i] : nullptr;
        SubResult& s = result.subproblems[i];
        if (resume && resume->phase == SubCheckpoint::Phase::finished) {
          s = resume->result;
          checkpoints.deposit(i, *resume, false);
        } else if (budget.exhausted()) {
          s = unstarted_subproblem(formulation, i);
          if (resume) checkpoints.deposit(i, *resume, false);
        } else {
          const formulate::SubProblem sub = formulation.subproblem(i);
          describe(sub, i, s);
          solve_subproblem(formulation, i, sub, resume, shared, tallies[i], s, nullptr);
        }
      } catch (...) {
        std::lock_guard lock(error_mutex);
        if (!error) error = std::current_exception();
        next.store(n);
      }
      tallies[i].finished.store(true);
    }
  };
  {
    Ticker ticker(options.progress, tallies, budget, checkpoints);
    std::vector<std::thread> pool;
    for (int t = 1; t < across; ++t)
      pool.emplace_back([&] {
        worker();
        rigorous::release_thread_caches();
      });
    worker();
    for (auto& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
  checkpoints.final_write();

  summarise(result, options, budget);
  result.cpu_seconds = process_cpu_seconds() - cpu_start;
  return result;
}

void summarise(CaseResult& result, const RunOptions& options, const Budget& budget) {
  const size_t n = result.subproblems.size();
  for (auto& s : result.subproblems) {
    result.total += s.stats;
    result.complete = result.complete && s.complete;
    result.pending_boxes += static_cast<long>(s.pending.size());
    result.volume_left += s.volume_left / static_cast<double>(n);
    // By name: sub-problems may have run different strategies ("auto" chooses per sub-problem).
    size_t k = 0;
    for (auto& name : s.strategy) {
      if (name == "/") continue;
      auto at = std::find(result.contractor_names.begin(), result.contractor_names.end(), name);
      if (at == result.contractor_names.end()) {
        result.contractor_names.push_back(name);
        result.counters.emplace_back();
        at = result.contractor_names.end() - 1;
      }
      if (k < s.counters.size()) result.counters[at - result.contractor_names.begin()] += s.counters[k];
      ++k;
    }
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
  result.seconds = budget.elapsed();
}

void Piece::merge(Piece&& o) {
  for (auto& n : o.state.pending) state.pending.push_back(std::move(n));
  for (auto& f : o.state.solutions) state.solutions.push_back(std::move(f));
  state.stats += o.state.stats;
  state.work += o.state.work;
  state.volume_done += o.state.volume_done;
  if (counters.empty()) counters.resize(o.counters.size());
  for (size_t k = 0; k < o.counters.size() && k < counters.size(); ++k) counters[k] += o.counters[k];
  if (race.empty()) race = std::move(o.race);
  if (strategy.empty()) strategy = std::move(o.strategy);
}

bool run_subproblem(const formulate::Formulation& formulation, size_t i, const RunOptions& options, Budget& budget,
                    Sharing* sharing, SubResult& s, Piece& piece) {
  const formulate::SubProblem sub = formulation.subproblem(i);
  describe(sub, i, s);
  RunOptions quiet = options;
  quiet.checkpoint.clear();
  Checkpointer none(quiet, 0);
  Shared shared{options, budget, none, options.threads, sharing};
  Tally tally;
  return solve_subproblem(formulation, i, sub, nullptr, shared, tally, s, &piece);
}

namespace {

// A search of sub-problem i with a strategy another process chose, over `state`'s boxes.
struct Resumed {
  Resumed(const formulate::Formulation& formulation, size_t i, const RunOptions& options, Budget& budget,
          const std::vector<std::string>& names, SearchState state)
      : sub(formulation.subproblem(i)),
        bisector(options.bisect, sub, options.params.sigma),
        ran(make_racer(formulation, i, sub, strategy_options(options), names)),
        search(sub.system.domain(), *ran->strategy.sequence, sub.split_dims, params_for(options, sub), budget,
               &ran->certifier, &bisector) {
    search.set_state(std::move(state));
  }
  formulate::SubProblem sub;
  Bisector bisector;
  std::unique_ptr<Racer> ran;
  Search search;
};

}  // namespace

// Records of a lent subtree go to the lender in batches of this many boxes (a few hundred
// kilobytes of JSON), so that they are there when its front gets to them.
constexpr size_t kRecordBatch = 512;

Piece run_subtree(const formulate::Formulation& formulation, size_t i, const RunOptions& options, Budget& budget,
                  Sharing* sharing, std::vector<std::string> strategy, std::vector<SearchState::Node> nodes, bool record) {
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
  return {i, std::move(strategy), r.search.state(), r.ran->strategy.sequence->counters(), {}};
}

SubResult finish_subproblem(const formulate::Formulation& formulation, size_t i, const RunOptions& options,
                            Budget& budget, Piece merged) {
  Resumed r(formulation, i, options, budget, merged.strategy, std::move(merged.state));
  r.ran->strategy.sequence->set_counters(merged.counters);
  SubResult s;
  describe(r.sub, i, s);
  s.bisect = to_string(r.bisector.rule());
  s.race = std::move(merged.race);
  const double work = r.search.work();
  finish(r.sub, params_for(options, r.sub), budget, *r.ran, r.bisector, r.search.result(), work, s);
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
