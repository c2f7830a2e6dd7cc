// Twins in a race (solve/race.hpp): hc4,newton/lp makes every box what hc4,newton makes it
// until hc4,newton's first stall, so the race may hand it hc4,newton's turn instead of running
// it. Taking the turn must change nothing but the time.
#include "formulate/load.hpp"
#include "solve/pruning.hpp"
#include "solve/race.hpp"
#include "solve/search.hpp"
#include "tests/cli_run.hpp"
#include "tests/same_search_state.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

using namespace linkbox;

namespace {

std::string source(const char* file) { return std::string(LINKBOX_SOURCE_DIR) + "/" + file; }

// Moré, Garbow and Hillstrom's discrete boundary value function in n unknowns (IbexSolve's
// DiscreteBoundary-00n.bch), as a Minibex file: few, costly boxes, none of them stalled.
std::string discrete_boundary(int n) {
  std::ostringstream m;
  m << "Constants\nh = 1/" << n + 1 << ";\nVariables\nx[" << n << "] in [-100,100];\nConstraints\n";
  for (int i = 1; i <= n; ++i)
    m << (i > 1 ? "-x(" + std::to_string(i - 1) + ") + " : "") << "2*x(" << i << ") + (h^2*(1 + " << i
      << "*h + x(" << i << "))^3)/2" << (i < n ? " - x(" + std::to_string(i + 1) + ")" : "") << " = 0;\n";
  m << "end\n";
  // ctest runs this file's test cases in parallel processes: each writes its own copy.
  const std::string path = test::scratch("discrete-boundary-" + std::to_string(n) + ".bch");
  std::ofstream(path) << m.str();
  return path;
}

struct Ran {
  std::vector<std::pair<std::string, double>> record;
  std::vector<std::string> choices;
  solve::SearchState winner;
  size_t twin_turns = 0;
};

// Sub-problem 0's "auto" race, run to its end on `threads`, as solve_case runs it.
Ran race(const formulate::Formulation& f, bool twins, int threads) {
  const formulate::SubProblem sub = f.subproblem(0);
  solve::StrategyOptions so;
  so.prune = solve::Strategy::parse("auto");
  so.stall = 0.99;  // as solve_case sets them (settings_for)
  solve::Params p;
  p.rho = 0.8;
  p.sigma = 0.1;
  solve::Budget budget(p);
  const solve::Bisector bisector(solve::Bisect::automatic, sub, p.sigma);
  std::vector<std::unique_ptr<solve::Racer>> racers;
  for (const solve::Strategy& s : solve::candidates(so.prune, sub)) {
    auto r = solve::make_racer(f, 0, sub, s, so);
    r->search = std::make_unique<solve::Search>(sub.system.domain(), *r->pruning.sequence, sub.split_dims, p, budget,
                                                &r->certifier, &bisector);
    racers.push_back(std::move(r));
  }
  solve::Race race(std::move(racers), nullptr, twins);
  while (!race.over()) {
    race.run_turn(threads);
    if (!race.over()) race.next_turn();
  }
  return {race.record(), race.choices(), race.best().search->state(), race.twin_turns()};
}

}  // namespace

TEST_CASE("until its first stall, a sequence with a later stage makes each box what its first stage makes it",
          "[race]") {
  // The discrete boundary function never stalls; brown-5 stalls in its first box.
  int compared = 0, stalled = 0;
  for (const std::string& file : {discrete_boundary(10), source("cases/benchmarks/brown-5.toml")}) {
    INFO(file);
    const formulate::LoadedCase c = formulate::load_case(file);
    const formulate::SubProblem sub = c.formulation->subproblem(0);
    solve::StrategyOptions so;
    so.stall = 0.99;  // as solve_case sets them (settings_for)
    solve::Params p;
    p.rho = 0.8;
    solve::Budget budget(p);
    solve::Pruning plain = solve::make_pruning(solve::Strategy::parse("hc4,newton"), so, sub);
    solve::Pruning staged = solve::make_pruning(solve::Strategy::parse("hc4,newton/lp"), so, sub);
    solve::Search a(sub.system.domain(), *plain.sequence, sub.split_dims, p, budget);
    solve::Search b(sub.system.domain(), *staged.sequence, sub.split_dims, p, budget);
    // One box at a time: `b` runs its LP stage first where `a` first stalls.
    for (double limit = 1; !a.complete(); limit += 1) {
      a.run(1, limit);
      b.run(1, limit);
      if (plain.sequence->stalls() > 0) {
        CHECK(staged.sequence->ran_later_stages());
        ++stalled;
        break;
      }
      CHECK_FALSE(staged.sequence->ran_later_stages());
      test::check_same_state(a.state(), b.state());
      ++compared;
    }
  }
  CHECK(compared > 0);
  CHECK(stalled == 1);
}

TEST_CASE("a race whose twins share turns is the race where each runs its own", "[race]") {
  // The discrete boundary functions: hc4,newton's first turn has no stall, so hc4,newton/lp
  // takes it; kin1 and brown-5: their LP stage runs in the first round.
  size_t taken = 0;
  for (const std::string& file : {discrete_boundary(10), discrete_boundary(20), source("cases/benchmarks/kin1.toml"),
                                  source("cases/benchmarks/brown-5.toml")}) {
    INFO(file);
    const formulate::LoadedCase c = formulate::load_case(file);
    for (int threads : {1, 2}) {
      INFO(threads << " threads");
      const Ran apart = race(*c.formulation, false, threads);
      const Ran shared = race(*c.formulation, true, threads);
      CHECK(apart.twin_turns == 0);
      CHECK(shared.record == apart.record);
      CHECK(shared.choices == apart.choices);
      test::check_same_state(shared.winner, apart.winner);
      taken += shared.twin_turns;
    }
  }
  CHECK(taken > 0);
}
