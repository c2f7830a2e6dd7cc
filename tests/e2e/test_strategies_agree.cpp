// Every strategy must certify the same roots on the bundled cases: the certified boxes of
// one strategy each overlap exactly one of another's (angles modulo 2 pi).
#include "formulate/load.hpp"
#include "interval/rigorous.hpp"
#include "solve/search.hpp"
#include "tests/same_search_state.hpp"
#include "solve/solve_case.hpp"
#include "solve/share.hpp"
#include "solve/pruning.hpp"

#include <algorithm>
#include <mutex>
#include <thread>
#include "verify/certify_case.hpp"
#include "verify/cluster.hpp"

#include <catch2/catch.hpp>

using namespace linkbox;

namespace {

std::vector<Box> certified_roots(const formulate::LoadedCase& c, const std::string& prune,
                                 prune::lp::Order order = prune::lp::Order::nearest_bound, long* lp_iterations = nullptr) {
  solve::RunOptions o;
  o.progress = false;
  o.strategy.prune = solve::Strategy::parse(prune);
  o.strategy.lp_order = order;
  auto r = solve::solve_case(*c.formulation, o);
  if (lp_iterations)
    for (auto& k : r.counters) *lp_iterations += k.lp_iterations;
  REQUIRE(r.complete);
  auto v = verify::verify_case(*c.formulation, r);
  CHECK(v.exact);
  std::vector<Box> roots;
  for (auto& cl : v.clusters)
    if (cl.status == verify::ClusterStatus::certified && cl.duplicate_of < 0) roots.push_back(cl.root);
  return roots;
}

}  // namespace

TEST_CASE("strategies agree on the certified roots of the bundled cases", "[strategies][slow]") {
  const std::vector<std::pair<std::string, std::vector<std::string>>> runs = {
      // "auto" first: it must find every root that a fixed strategy certifies, and no other.
      {"cases/spherical/wrist.toml", {"auto", "trapezoid", "trapezoid,newton", "hc4,newton", "lp", "hc4,lp"}},
      {"cases/spherical/agile-eye.toml", {"auto", "trapezoid", "trapezoid,newton", "trapezoid,lp"}},
      {"cases/polynomial/circle-line.toml", {"auto", "hc4", "newton", "lp", "hc4,lp"}},
      {"cases/polynomial/planted-cubic.toml", {"auto", "hc4", "newton", "hc4,lp", "acid,newton", "taylor,newton"}},
      {"cases/benchmarks/kin1.toml", {"auto", "hc4,newton", "hc4,newton/lp", "hc4,acid,newton", "hc4,newton,taylor"}},
      {"cases/benchmarks/cyclohexan3d.toml", {"auto", "hc4,newton", "hc4,lp", "hc4,acid,newton"}},
      {"cases/benchmarks/caprasse.toml", {"auto", "hc4,acid,newton"}},
      {"cases/linkages/6r-rigid.toml", {"auto", "hc4/newton", "hc4,acid,newton", "hc4,newton/taylor"}},
  };
  for (auto& [file, strategies] : runs) {
    formulate::LoadedCase c = formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/" + file);
    const std::vector<bool> periodic(c.formulation->output_names().size(), c.formulation->outputs_are_angles());
    const auto reference = certified_roots(c, strategies[0]);
    CHECK(!reference.empty());
    for (size_t s = 1; s < strategies.size(); ++s) {
      INFO(file << " strategy " << s);
      const auto other = certified_roots(c, strategies[s]);
      REQUIRE(other.size() == reference.size());
      for (auto& a : other) {
        int matches = 0;
        for (auto& b : reference) matches += verify::boxes_touch(a, b, periodic);
        CHECK(matches == 1);
      }
    }
  }
}

TEST_CASE("the lp contractor in either bound order certifies the same roots", "[strategies]") {
  // The order reaches the contractor (the simplex pivots differ), and neither loses a root.
  for (auto [file, prune] : {std::pair{"cases/benchmarks/cyclohexan3d.toml", "hc4,lp"},
                             std::pair{"cases/spherical/wrist.toml", "lp"}}) {
    INFO(file);
    formulate::LoadedCase c = formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/" + file);
    const std::vector<bool> periodic(c.formulation->output_names().size(), c.formulation->outputs_are_angles());
    long given_pivots = 0, nearest_pivots = 0;
    const auto given = certified_roots(c, prune, prune::lp::Order::given, &given_pivots);
    const auto nearest = certified_roots(c, prune, prune::lp::Order::nearest_bound, &nearest_pivots);
    CHECK(given_pivots != nearest_pivots);
    REQUIRE(!given.empty());
    REQUIRE(nearest.size() == given.size());
    for (auto& a : nearest) {
      int matches = 0;
      for (auto& b : given) matches += verify::boxes_touch(a, b, periodic);
      CHECK(matches == 1);
    }
  }
}

TEST_CASE("each contractor reports its own work, LPs included", "[strategies]") {
  formulate::LoadedCase c = formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/cases/polynomial/planted-cubic.toml");
  solve::RunOptions o;
  o.progress = false;
  o.strategy.prune = solve::Strategy::parse("hc4,lp");
  auto r = solve::solve_case(*c.formulation, o);
  REQUIRE(r.complete);
  REQUIRE(r.counters.size() == 2);
  const auto &hc4 = r.counters[0], &lp = r.counters[1];
  CHECK(hc4.calls > 0);
  CHECK(hc4.lps_solved == 0);
  CHECK(hc4.lp_iterations == 0);
  // Each LP call that gets past its interval checks solves a min and a max per variable of
  // the lifted system's primary part (x, y, z), at most 6 LPs, and CLP pivots on some.
  CHECK(lp.calls > 0);
  CHECK(lp.lps_solved > 0);
  CHECK(lp.lps_solved <= 6 * lp.calls);
  CHECK(lp.lp_iterations > 0);
}

TEST_CASE("a race on several threads picks the winner and boxes of the one-thread race", "[strategies]") {
  // brown-5: the LP candidate's first box passes the first round's cap (race.cpp), so a
  // capped box is met in look-ahead mode too.
  for (const char* file : {"cases/benchmarks/kin1.toml", "cases/linkages/6r-rigid.toml", "cases/linkages/cyclohexane.toml",
                           "cases/benchmarks/brown-5.toml"}) {
    INFO(file);
    const formulate::LoadedCase c = formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/" + file);
    solve::RunOptions o;
    o.progress = false;
    o.params.sigma = 0.1;
    o.threads = 1;
    const auto one = solve::solve_case(*c.formulation, o);
    REQUIRE(one.subproblems.size() == 1);
    const auto& a = one.subproblems[0];
    REQUIRE(a.race.size() == 3);  // "auto" raced three candidates
    // Why: every choice of the lead names each candidate; the last line, the winner.
    REQUIRE(a.race_choices.size() >= 1);
    for (size_t k = 0; k + 1 < a.race_choices.size(); ++k)
      if (a.race_choices[k].find("the lead") != std::string::npos)
        for (auto& [name, work] : a.race) CHECK(a.race_choices[k].find(name + " work") != std::string::npos);
    CHECK(a.race_choices.back().rfind(a.race.back().first + " finished its search first", 0) == 0);
    if (std::string(file).find("brown") != std::string::npos) {
      CHECK(a.race_choices.front().find("stopped at a box costing over") != std::string::npos);
      CHECK(std::count(a.certified.begin(), a.certified.end(), 1) == 3);  // a = 1 and the quartic's two real roots
    }
    for (int threads : {2, 3, 4}) {
      INFO(threads << " threads");
      o.threads = threads;
      const auto many = solve::solve_case(*c.formulation, o);
      REQUIRE(many.subproblems.size() == 1);
      const auto& b = many.subproblems[0];
      CHECK(a.strategy == b.strategy);
      CHECK(a.race == b.race);  // every turn ended at the same box: the same work, loser included
      CHECK(a.race_choices == b.race_choices);
      CHECK(a.stats.processed == b.stats.processed);
      REQUIRE(a.solutions.size() == b.solutions.size());
      for (size_t k = 0; k < a.solutions.size(); ++k)
        for (size_t j = 0; j < a.solutions[k].size(); ++j) {
          CHECK(a.solutions[k][j].lower() == b.solutions[k][j].lower());
          CHECK(a.solutions[k][j].upper() == b.solutions[k][j].upper());
        }
      CHECK(a.certified == b.certified);
    }
  }
}

namespace {

// The 6R's search with `hc4,newton/lp`, run to growing work limits on `threads`; the first
// `capped_runs` runs also with growing box caps. Its state at each stop, and whether it was
// capped.
struct Stop {
  solve::SearchState state;
  bool capped;
};

std::vector<Stop> stops_of_6r(int threads, int capped_runs) {
  static const formulate::LoadedCase c =
      formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/cases/linkages/6r-rigid.toml");
  const formulate::SubProblem sub = c.formulation->subproblem(0);
  solve::StrategyOptions so;
  so.prune = solve::Strategy::parse("hc4,newton/lp");
  solve::Params p;
  p.rho = 0.8;
  solve::Pruning strategy = solve::make_pruning(so.prune, so, sub);
  solve::Budget budget(p);
  solve::Search search(sub.system.domain(), *strategy.sequence, sub.split_dims, p, budget);
  std::vector<Stop> out;
  double limit = 50, box_cap = 2;
  for (int k = 0; !search.complete(); ++k, limit *= 1.5, box_cap *= 1.5) {
    search.run(threads, limit, k < capped_runs ? box_cap : 0);
    out.push_back({search.state(), search.capped()});
  }
  return out;
}

}  // namespace

TEST_CASE("a search cut at work limits stops at the same box on any number of threads", "[strategies]") {
  // Look-ahead mode (Search::run with threads and a limit): helpers shrink boxes ahead of the
  // depth-first front, the front takes their results in order. At every stop the state must be
  // the one-thread search's: the same pending boxes, solutions and work.
  const auto one = stops_of_6r(1, 0);
  const auto three = stops_of_6r(3, 0);
  REQUIRE(one.size() > 5);
  REQUIRE(one.size() == three.size());
  for (size_t k = 0; k < one.size(); ++k) {
    INFO("stop " << k);
    test::check_same_state(one[k].state, three[k].state);
  }
}

TEST_CASE("a search with capped boxes stops at the same box on any number of threads", "[strategies]") {
  // A capped box ends the run and goes back as far as its passes shrank it, its work counted;
  // caps grow, then none. Each stop must be the one-thread search's, and the end must hold the
  // uncapped search's certified roots.
  const auto one = stops_of_6r(1, 12);
  const auto three = stops_of_6r(3, 12);
  const auto uncapped = stops_of_6r(1, 0);
  REQUIRE(std::count_if(one.begin(), one.end(), [](const Stop& s) { return s.capped; }) >= 2);
  REQUIRE(one.size() == three.size());
  for (size_t k = 0; k < one.size(); ++k) {
    INFO("stop " << k);
    CHECK(one[k].capped == three[k].capped);
    test::check_same_state(one[k].state, three[k].state);
  }
  // The box a run capped is the one the next run takes, inside the box the run before listed
  // under its path, and the capped run's work counts.
  int kept = 0;
  for (size_t k = 1; k < one.size(); ++k) {
    if (!one[k].capped) continue;
    INFO("stop " << k);
    CHECK(one[k].state.work > one[k - 1].state.work);
    const auto& top = one[k].state.pending.back();
    for (const auto& before : one[k - 1].state.pending)
      if (before.path == top.path) {
        CHECK(contains(before.box, top.box));
        kept += !std::equal(top.box.begin(), top.box.end(), before.box.begin(), [](const Interval& x, const Interval& y) {
          return x.lower() == y.lower() && x.upper() == y.upper();
        });
      }
  }
  CHECK(kept >= 1);
  auto certified = [](const solve::SearchState& s) {
    std::vector<Box> r;
    for (const auto& f : s.solutions)
      if (f.certified) r.push_back(f.box);
    return r;
  };
  const auto roots = certified(one.back().state), reference = certified(uncapped.back().state);
  REQUIRE(roots.size() == reference.size());
  for (const auto& a : roots) {
    int matches = 0;
    for (const auto& b : reference) matches += verify::boxes_touch(a, b, std::vector<bool>(a.size(), false));
    CHECK(matches == 1);
  }
}

namespace {

// Lends the race leader's boxes as a distributed run would, but to threads of this process:
// each lent box's subtree is searched with records on and its records delivered back.
struct ThreadLending final : solve::Sharing {
  const formulate::Formulation& f;
  const solve::RunOptions& options;
  solve::Budget& budget;
  int calls = 0;
  bool wanted = false;  // as a steal request: asked() says so until lend() answers it
  int lent = 0;
  std::mutex m;
  long lease = 0;  // as a distributed run's: records of recalled boxes are dropped
  std::vector<std::thread> threads;
  ThreadLending(const formulate::Formulation& f, const solve::RunOptions& o, solve::Budget& b) : f(f), options(o), budget(b) {}
  bool asked() override {  // now and then, as steal requests come
    if (!wanted && ++calls % 7 == 0) wanted = true;
    return wanted;
  }
  bool give(size_t, const solve::Strategy&, solve::Lender&) override { return false; }
  bool lend(size_t i, const solve::Strategy& strategy, solve::Lender& search) override {
    wanted = false;
    auto node = search.lend();
    if (!node) return false;
    ++lent;
    threads.emplace_back([this, i, strategy, n = *node, &search, lease = lease] {
      solve::Piece p = solve::run_subtree(f, i, options, budget, nullptr, strategy, {n}, true);
      {
        std::lock_guard lock(m);
        if (lease == this->lease) search.deliver(std::move(p.state.records), p.counters);  // else recalled
      }
      rigorous::release_thread_caches();  // MPFR's per-thread caches, as every thread of the library does
    });
    return true;
  }
  void recall() override {
    std::lock_guard lock(m);
    ++lease;
  }
  void end_lending() override {
    for (auto& t : threads) t.join();
    threads.clear();
  }
};

}  // namespace

TEST_CASE("a race whose leader lends boxes ends as the one-process race", "[strategies]") {
  // The owner's front takes the lent subtrees' records in depth-first order (waiting for
  // them), so every turn ends at the same box: the same winner, work, counts and boxes.
  for (const char* file : {"cases/linkages/6r-rigid.toml", "cases/benchmarks/caprasse.toml"}) {
    INFO(file);
    const formulate::LoadedCase c = formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/" + file);
    solve::RunOptions o;
    o.progress = false;
    solve::SubResult one, lent;
    solve::Piece piece;
    {
      solve::Budget budget(o.params);
      REQUIRE(solve::run_subproblem(*c.formulation, 0, o, budget, nullptr, one, piece));
    }
    o.threads = 2;  // the lender's own helpers too
    solve::Budget budget(o.params);
    ThreadLending lending(*c.formulation, o, budget);
    REQUIRE(solve::run_subproblem(*c.formulation, 0, o, budget, &lending, lent, piece));
    CHECK(lending.lent > 0);
    REQUIRE(one.race.size() == 3);
    CHECK(one.race == lent.race);
    CHECK(one.race_choices == lent.race_choices);
    CHECK(one.strategy == lent.strategy);
    CHECK(one.stats.processed == lent.stats.processed);
    CHECK(one.stats.split == lent.stats.split);
    CHECK(one.stats.shrinks == lent.stats.shrinks);
    CHECK(one.certified == lent.certified);
    REQUIRE(one.solutions.size() == lent.solutions.size());
    for (size_t k = 0; k < one.solutions.size(); ++k)
      for (size_t j = 0; j < one.solutions[k].size(); ++j) {
        CHECK(one.solutions[k][j].lower() == lent.solutions[k][j].lower());
        CHECK(one.solutions[k][j].upper() == lent.solutions[k][j].upper());
      }
  }
}

TEST_CASE("a lending race stopped by a box limit keeps every root in a solution or pending box", "[strategies]") {
  // The lent boxes stay listed: whatever the limit cuts off, the pending boxes (lent ones and
  // halves from records included) and the solutions still cover every root.
  const formulate::LoadedCase c = formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/cases/benchmarks/caprasse.toml");
  solve::RunOptions o;
  o.progress = false;
  solve::SubResult full;
  solve::Piece piece;
  {
    solve::Budget budget(o.params);
    REQUIRE(solve::run_subproblem(*c.formulation, 0, o, budget, nullptr, full, piece));
  }
  auto inside = [](const Box& a, const Box& b) {
    for (size_t d = 0; d < a.size(); ++d)
      if (a[d].lower() < b[d].lower() || a[d].upper() > b[d].upper()) return false;
    return true;
  };
  for (long limit : {full.stats.processed / 3, 2 * full.stats.processed / 3}) {
    INFO("max boxes " << limit);
    o.params.max_boxes = limit;
    solve::Budget budget(o.params);
    ThreadLending lending(*c.formulation, o, budget);
    solve::SubResult part;
    REQUIRE(solve::run_subproblem(*c.formulation, 0, o, budget, &lending, part, piece));
    CHECK_FALSE(part.complete);
    CHECK(lending.lent > 0);
    for (const Box& root : full.solutions) {
      bool covered = false;
      for (const Box& b : part.solutions) covered = covered || inside(root, b);
      for (const Box& b : part.pending) covered = covered || inside(root, b);
      CHECK(covered);
    }
  }
}
