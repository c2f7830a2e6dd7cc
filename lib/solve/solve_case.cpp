#include "solve/solve_case.hpp"

#include <condition_variable>
#include <cstdio>
#include <mutex>
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
          auto contractor = make_strategy(options.strategy, sub);
          Result r = branch_and_prune(sub.system.domain(), *contractor, sub.split_dims, options.params, budget, inside);
          s.solutions = std::move(r.solutions);
          for (auto& b : s.solutions) s.residuals.push_back(model::residual_bound(sub.system.equations, b));
          s.stats = r.stats;
          s.complete = r.complete;
          s.counters = contractor->counters();
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
    if (result.counters.size() < s.counters.size()) result.counters.resize(s.counters.size());
    for (size_t k = 0; k < s.counters.size(); ++k) result.counters[k] += s.counters[k];
  }
  result.contractor_names = options.strategy.contractors;
  result.rigorous = options.strategy.arith == Arith::verified;
  if (!result.complete) result.stop_reason = budget.reason();
  result.seconds = budget.elapsed();
  return result;
}

}  // namespace linkbox::solve
