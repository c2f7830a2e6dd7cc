// Every strategy must certify the same roots on the bundled cases: the certified boxes of
// one strategy each overlap exactly one of another's (angles modulo 2 pi).
#include "formulate/load.hpp"
#include "solve/solve_case.hpp"
#include "verify/certify_case.hpp"
#include "verify/cluster.hpp"

#include <catch2/catch.hpp>

using namespace linkbox;

namespace {

std::vector<Box> certified_roots(const formulate::LoadedCase& c, const std::vector<std::string>& prune) {
  solve::RunOptions o;
  o.progress = false;
  o.strategy.contractors = prune;
  auto r = solve::solve_case(*c.formulation, o);
  REQUIRE(r.complete);
  auto v = verify::verify_case(*c.formulation, r);
  CHECK(v.exact);
  std::vector<Box> roots;
  for (auto& cl : v.clusters)
    if (cl.status == verify::ClusterStatus::certified && cl.duplicate_of < 0) roots.push_back(cl.root);
  return roots;
}

}  // namespace

TEST_CASE("strategies agree on the certified roots of the bundled cases", "[strategies]") {
  const std::vector<std::pair<std::string, std::vector<std::vector<std::string>>>> runs = {
      // "auto" first: it must find every root that a fixed strategy certifies, and no other.
      {"cases/spherical/wrist.toml", {{"auto"}, {"trapezoid"}, {"trapezoid", "newton"}, {"hc4", "newton"}, {"lp"}, {"hc4", "lp"}}},
      {"cases/spherical/agile-eye.toml", {{"auto"}, {"trapezoid"}, {"trapezoid", "newton"}, {"trapezoid", "lp"}}},
      {"cases/polynomial/circle-line.toml", {{"auto"}, {"hc4"}, {"newton"}, {"lp"}, {"hc4", "lp"}}},
      {"cases/polynomial/planted-cubic.toml", {{"auto"}, {"hc4"}, {"newton"}, {"hc4", "lp"}, {"acid", "newton"}}},
      {"cases/benchmarks/kin1.toml", {{"auto"}, {"hc4", "newton"}, {"hc4", "newton", "/", "lp"}, {"hc4", "acid", "newton"}}},
      {"cases/benchmarks/cyclohexan3d.toml", {{"auto"}, {"hc4", "newton"}, {"hc4", "lp"}, {"hc4", "acid", "newton"}}},
      {"cases/benchmarks/caprasse.toml", {{"auto"}, {"hc4", "acid", "newton"}}},
      {"cases/linkages/6r-rigid.toml", {{"auto"}, {"hc4", "/", "newton"}, {"hc4", "acid", "newton"}}},
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

TEST_CASE("each contractor reports its own work, LPs included", "[strategies]") {
  formulate::LoadedCase c = formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/cases/polynomial/planted-cubic.toml");
  solve::RunOptions o;
  o.progress = false;
  o.strategy.contractors = {"hc4", "lp"};
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

TEST_CASE("a race run side by side on two threads picks the winner and boxes of the one-thread race", "[strategies]") {
  for (const char* file : {"cases/benchmarks/kin1.toml", "cases/linkages/6r-rigid.toml", "cases/linkages/cyclohexane.toml"}) {
    INFO(file);
    const formulate::LoadedCase c = formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/" + file);
    solve::RunOptions o;
    o.progress = false;
    o.params.sigma = 0.1;
    o.threads = 1;
    const auto one = solve::solve_case(*c.formulation, o);
    o.threads = 2;
    const auto two = solve::solve_case(*c.formulation, o);
    REQUIRE(one.subproblems.size() == 1);
    REQUIRE(two.subproblems.size() == 1);
    const auto &a = one.subproblems[0], &b = two.subproblems[0];
    REQUIRE(a.race.size() == 2);  // "auto" raced two candidates
    REQUIRE(b.race.size() == 2);
    CHECK(a.strategy == b.strategy);
    CHECK(a.race.back() == b.race.back());  // the winner, and its work to the last box
    CHECK(b.race.front().second >= a.race.front().second);  // a loser may have run its last turn too
    REQUIRE(a.solutions.size() == b.solutions.size());
    for (size_t k = 0; k < a.solutions.size(); ++k)
      for (size_t j = 0; j < a.solutions[k].size(); ++j) {
        CHECK(a.solutions[k][j].lower() == b.solutions[k][j].lower());
        CHECK(a.solutions[k][j].upper() == b.solutions[k][j].upper());
      }
    CHECK(a.certified == b.certified);
  }
}
