#include "solve/solve_case.hpp"

#include "solve/checkpoint.hpp"
#include "solve/pool.hpp"
#include "solve/progress.hpp"
#include "solve/subproblem.hpp"
#include "solve/summary.hpp"

#include <algorithm>
#include <stdexcept>

#include <sys/resource.h>

namespace linkbox::solve {

namespace {

double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Sub-problem i of the run, into `s`: from the checkpoint when it had finished there, not
// started once a limit was reached, else searched.
void run_one(const formulate::Formulation& formulation, size_t i, const SubCheckpoint* resume, Shared& run, Tally& tally,
             SubResult& s) {
  if (resume && resume->phase == SubCheckpoint::Phase::finished) {
    s = resume->result;
    run.checkpoints.deposit(i, *resume, false);
  } else if (run.budget.exhausted()) {
    s = unstarted_subproblem(formulation, i);
    if (resume) run.checkpoints.deposit(i, *resume, false);
  } else {
    const formulate::SubProblem sub = formulation.subproblem(i);
    describe(sub, i, s);
    solve_subproblem(formulation, i, sub, resume, run, tally, s, nullptr);
  }
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
  Checkpointer checkpoints(options.checkpoint, options.checkpoint_every, options.checkpoint_header, n);
  std::vector<Tally> tallies(n);
  // Threads go across sub-problems when there are enough of them, else inside each one.
  const int across = std::max(1, std::min<int>(options.threads, static_cast<int>(n)));
  Shared shared{options, budget, checkpoints, n >= static_cast<size_t>(options.threads) ? 1 : options.threads};
  {
    Ticker ticker(options.progress, tallies, budget, checkpoints);
    run_jobs(n, across, [&](size_t i) {
      const SubCheckpoint* resume = options.resume ? &options.resume->subproblems[i] : nullptr;
      try {
        run_one(formulation, i, resume, shared, tallies[i], result.subproblems[i]);
      } catch (...) {
        tallies[i].finished.store(true);
        throw;
      }
      tallies[i].finished.store(true);
    });
  }
  checkpoints.final_write();

  summarise(result, options, budget);
  result.cpu_seconds = process_cpu_seconds() - cpu_start;
  return result;
}

}  // namespace linkbox::solve
