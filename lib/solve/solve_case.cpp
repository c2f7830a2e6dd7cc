#include "solve/solve_case.hpp"

#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <algorithm>
#include <thread>

namespace linkbox::solve {

namespace {

// Prints a progress line every second until stopped; silent for runs under a second.
class Progress {
 public:
  Progress(bool enabled, size_t total, const Budget& budget, const std::atomic<size_t>& done)
      : total_(total), budget_(budget), done_(done) {
    if (enabled) thread_ = std::thread([this] { run(); });
  }
  ~Progress() {
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
    while (!cv_.wait_for(lock, std::chrono::seconds(1), [this] { return stop_; }))
      std::fprintf(stderr, "linkbox: %zu/%zu sub-problems, %ld boxes, %.1f s\n", done_.load(), total_,
                   budget_.boxes_taken(), budget_.elapsed());
  }
  size_t total_;
  const Budget& budget_;
  const std::atomic<size_t>& done_;
  std::mutex m_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace

namespace {

struct Racer {
  Strategy strategy;
  NaturalCertifier certifier;
  std::unique_ptr<Search> search;
};

// "auto" on a system with several candidates: their searches advance in turns, measured in
// work (boxes + kLpWork per LP), until one finishes; its boxes are the result, as if it had
// run alone. Turns double. After a first turn each, the candidate whose projected total work
// (work / share of the volume resolved) is smaller gets the turn and the others kRaceShare of
// it, so a wrong projection costs a bounded factor. A race runs in one thread, so where it
// stops is deterministic.
constexpr double kRaceShare = 0.125;
constexpr double kFirstTurn = 4000;

double projected(const Search& s) { return s.work() / std::max(s.fraction_done(), 1e-9); }

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
constexpr size_t kRefineMax = 4000;

// Per uncertified solution box: whether its group of touching uncertified boxes is small.
std::vector<char> in_small_group(const Result& r) {
  std::vector<size_t> open;
  for (size_t k = 0; k < r.solutions.size(); ++k)
    if (!r.certified[k]) open.push_back(k);
  std::vector<char> small(r.solutions.size(), 0);
  if (open.size() > kRefineMax) return small;
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
  for (size_t a = 0; a < open.size(); ++a) small[open[a]] = size[group[a]] <= kRefineGroup;
  return small;
}

void refine(Result& r, double search_work, const formulate::SubProblem& sub, const Params& params, Budget& budget,
            prune::Sequence& contractor, Certifier& certifier, const Bisector& bisector) {
  Params fine = params;
  double allowance = 2 * search_work + 20 * kRefineWork;
  for (int round = 0; round < kRefineRounds; ++round) {
    fine.sigma = std::max(fine.sigma * kRefineFactor, kSigmaFloor);
    Result out;
    bool changed = false;
    const std::vector<char> small = in_small_group(r);
    for (size_t k = 0; k < r.solutions.size(); ++k) {
      if (r.certified[k] || !small[k] || budget.exhausted() || fine.sigma >= params.sigma || allowance <= 0) {
        out.solutions.push_back(std::move(r.solutions[k]));
        out.certified.push_back(r.certified[k]);
        continue;
      }
      Search search(r.solutions[k], contractor, sub.split_dims, fine, budget, &certifier, &bisector);
      const bool finished = search.run(1, std::min(kRefineWork, allowance));
      allowance -= search.work();
      Result part = search.result();
      if (!finished || !part.complete) {  // stopped by a limit: keep the box as it was
        out.solutions.push_back(std::move(r.solutions[k]));
        out.certified.push_back(false);
        continue;
      }
      changed = true;
      const double seconds = r.stats.seconds;
      r.stats += part.stats;  // the box was counted as a solution once: its search replaces it
      r.stats.seconds = seconds + part.stats.seconds;
      for (size_t j = 0; j < part.solutions.size(); ++j) {
        out.solutions.push_back(std::move(part.solutions[j]));
        out.certified.push_back(part.certified[j]);
      }
    }
    r.solutions = std::move(out.solutions);
    r.certified = std::move(out.certified);
    if (!changed) break;
  }
  r.stats.solution = static_cast<long>(r.solutions.size());
  r.stats.certified = std::count(r.certified.begin(), r.certified.end(), 1);
}

void solve_subproblem(const formulate::Formulation& formulation, size_t i, const formulate::SubProblem& sub,
                      const RunOptions& options, Budget& budget, int threads, SubResult& s) {
  StrategyOptions strategy = options.strategy;
  strategy.stall = options.params.rho;
  std::vector<std::vector<std::string>> candidates{strategy.contractors};
  if (strategy.contractors == std::vector<std::string>{"auto"}) candidates = auto_candidates(sub);
  const Bisector bisector(options.bisect, sub, options.params.sigma);
  s.bisect = to_string(bisector.rule());
  std::vector<std::unique_ptr<Racer>> racers;
  for (auto& names : candidates) {
    strategy.contractors = names;
    auto r = std::unique_ptr<Racer>(new Racer{make_strategy(strategy, sub), NaturalCertifier(formulation, i), nullptr});
    r->search = std::make_unique<Search>(sub.system.domain(), *r->strategy.sequence, sub.split_dims, options.params,
                                         budget, &r->certifier, &bisector);
    racers.push_back(std::move(r));
  }
  Racer* winner = nullptr;
  if (racers.size() == 1) {
    racers[0]->search->run(threads);
    winner = racers[0].get();
  }
  for (double turn = kFirstTurn; !winner; turn *= 2) {
    size_t lead = 0;
    if (turn > kFirstTurn)
      for (size_t k = 1; k < racers.size(); ++k)
        if (projected(*racers[k]->search) < projected(*racers[lead]->search)) lead = k;
    for (size_t k = 0; k < racers.size() && !winner; ++k) {
      // First turn: the costlier candidates get the share too (their projection needs little).
      const double share = k == lead && (k == 0 || turn > kFirstTurn) ? 1 : kRaceShare;
      if (racers[k]->search->run(1, racers[k]->search->work() + turn * share)) winner = racers[k].get();
    }
  }
  for (auto& r : racers)
    if (r.get() != winner) s.race.push_back({strategy_name(r->strategy.names), r->search->work()});
  if (racers.size() > 1) s.race.push_back({strategy_name(winner->strategy.names), winner->search->work()});

  s.strategy = winner->strategy.names;
  Result r = winner->search->result();
  // Only Newton tells the certifier where to look; without it a refinement cannot certify.
  const auto& names = winner->strategy.names;
  if (r.complete && std::find(names.begin(), names.end(), "newton") != names.end()) refine(r, winner->search->work(), sub, options.params, budget, *winner->strategy.sequence, winner->certifier, bisector);
  s.solutions = std::move(r.solutions);
  s.certified = std::move(r.certified);
  for (auto& b : s.solutions) s.residuals.push_back(model::residual_bound(sub.system.equations, b));
  s.stats = r.stats;
  s.complete = r.complete;
  s.counters = winner->strategy.sequence->counters();
}

}  // namespace

CaseResult solve_case(const formulate::Formulation& formulation, const RunOptions& options) {
  const size_t n = formulation.subproblem_count();
  CaseResult result;
  result.subproblems.resize(n);
  Budget budget(options.params);
  // Threads go across sub-problems when there are enough of them, else inside each one.
  const int across = std::max(1, std::min<int>(options.threads, static_cast<int>(n)));
  const int inside = n >= static_cast<size_t>(options.threads) ? 1 : options.threads;
  std::atomic<size_t> next{0}, done{0};
  std::exception_ptr error;
  std::mutex error_mutex;

  auto worker = [&] {
    for (size_t i; (i = next.fetch_add(1)) < n;) {
      try {
        formulate::SubProblem sub = formulation.subproblem(i);
        SubResult& s = result.subproblems[i];
        s.index = i;
        s.label = sub.label;
        s.equations = static_cast<int>(sub.system.equations.size());
        s.variables = static_cast<int>(sub.system.variables.size());
        if (budget.exhausted()) {
          s.complete = false;
        } else {
          solve_subproblem(formulation, i, sub, options, budget, inside, s);
        }
      } catch (...) {
        std::lock_guard lock(error_mutex);
        if (!error) error = std::current_exception();
        next.store(n);
      }
      done.fetch_add(1);
    }
  };
  {
    Progress progress(options.progress, n, budget, done);
    std::vector<std::thread> pool;
    for (int t = 1; t < across; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);

  for (auto& s : result.subproblems) {
    result.total += s.stats;
    result.complete = result.complete && s.complete;
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
      break;
    }
  result.rigorous = options.strategy.arith == Arith::verified;
  if (!result.complete) result.stop_reason = budget.reason();
  result.seconds = budget.elapsed();
  return result;
}

}  // namespace linkbox::solve
