// Bicyclohexane's isolated poses are roots of 14 equations in 13 unknowns: a ring in a chair
// (rigid) beside a ring on its boat curve, tied by the bridgehead angles. They are certified
// through the loops (verify/coupled_loops.hpp), here in windows of joint limits around them.
#include "formulate/load.hpp"
#include "tests/bicyclohexane_window.hpp"
#include "tests/solved_case.hpp"
#include "verify/check.hpp"
#include "verify/coupled_loops.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace linkbox;

namespace {

test::SolvedCase solve_window(const std::string& text) { return test::solve_text(text, "auto", 0.1); }

}  // namespace

TEST_CASE("bicyclohexane: a chair beside a boat is certified through its loops", "[linkage][coupled]") {
  const auto run = solve_window(test::bicyclohexane_window(test::bicyclohexane_text(), test::bicyclohexane_pose('b')));
  // The window holds the pose and its mirror in ring 2's turn about c1-c2.
  REQUIRE(run.roots.size() == 2);
  CHECK(run.j["certified_roots"] == 2);
  CHECK(run.j["headline"].get<std::string>().find("exactly 2 roots") != std::string::npos);
  std::vector<double> turns;
  for (auto& c : run.j["clusters"]) {
    if (c["status"] != "certified") continue;
    CHECK(c["argument"] == "coupled loops");
    CHECK(c["certificate"]["unique_in_hull"] == true);
    CHECK(c["reason"].get<std::string>().find("'ring1' rigid") != std::string::npos);
    const auto& root = c["root"];
    const auto mid = [&](int i) { return (root[i][0].get<double>() + root[i][1].get<double>()) / 2; };
    // Ring 1 is the chair of the closed form, ring 2 a boat: torsions i and i + 3 alike.
    for (int i = 0; i < 6; ++i) CHECK(std::fabs(std::fabs(mid(i)) - test::chair_torsion()) < 1e-9);
    CHECK(std::fabs(mid(11) - mid(8)) < 1e-9);  // c1-c2@ring2 and c8-c9
    CHECK(std::fabs(mid(6) - mid(9)) < 1e-9);   // c2-c7 and c9-c10
    CHECK(std::fabs(mid(7) - mid(10)) < 1e-9);  // c7-c8 and c10-c1
    turns.push_back(mid(12));
  }
  REQUIRE(turns.size() == 2);
  CHECK(std::fabs(turns[0] + turns[1]) < 1e-9);
  CHECK(verify::check_certificates(run.j, *run.c.formulation).failures.empty());
}

TEST_CASE("bicyclohexane: the iterated LP's wider boxes give the same poses, certified", "[linkage][coupled]") {
  // With the paper's pruning the window is one solution box: the subsystem's root is unique
  // only around its certified box, so each pose is certified without the hull's uniqueness.
  const auto run = test::solve_text(test::bicyclohexane_window(test::bicyclohexane_text(), test::bicyclohexane_pose('b')),
                                    "lp", 0.1);
  CHECK(run.roots.size() == 2);
  for (auto& c : run.v.clusters)
    if (c.status == verify::ClusterStatus::certified) CHECK(c.argument == "coupled loops");
  CHECK(verify::check_certificates(run.j, *run.c.formulation).failures.empty());
}

namespace {

// `text` with the first occurrence of `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("bicyclohexane: two chairs make the bridgeheads one equation, certified", "[linkage][coupled]") {
  const std::string window = test::bicyclohexane_window(test::bicyclohexane_text(), test::bicyclohexane_pose('c'));
  const auto run = solve_window(window);
  // The window holds the pose and its mirror in ring 2's turn about c1-c2.
  REQUIRE(run.roots.size() == 2);
  CHECK(run.j["headline"].get<std::string>().find("exactly 2 roots") != std::string::npos);
  for (auto& c : run.j["clusters"]) {
    if (c["status"] != "certified") continue;
    CHECK(c["argument"] == "coupled loops");
    const std::string twin =
        "'bridgehead c2' and 'bridgehead c1' at the ends of the joint 'c1-c2' they share are one equation";
    CHECK(c["reason"].get<std::string>().find(twin) != std::string::npos);
    const auto& root = c["root"];
    const auto mid = [&](int i) { return (root[i][0].get<double>() + root[i][1].get<double>()) / 2; };
    for (int i = 0; i < 12; ++i) CHECK(std::fabs(std::fabs(mid(i)) - test::chair_torsion()) < 1e-9);
    CHECK(std::fabs(mid(11) - mid(0)) < 1e-12);  // c1-c2@ring2 and c1-c2: the same chair
  }
  CHECK(verify::check_certificates(run.j, *run.c.formulation).failures.empty());

  // Where the argument's premises fail, the poses need not exist: nothing is proved at the
  // same boxes, and check rejects the claim. By the next double, so that only the premises,
  // not the final test that every equation contains 0 on the box, can tell.
  for (auto [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"angle = 1.91", "angle = 1.9100000000000001"},  // the bridgeheads ask different angles
           // Ring 2 is no longer ring 1.
           {"link = \"c8\",  a = 0, d = 1.526, alpha = 1.23",
            "link = \"c8\",  a = 0, d = 1.526, alpha = 1.2300000000000002"}}) {
    INFO(to);
    const auto perturbed = formulate::load_case_text(replaced(window, from, to), "perturbed.toml");
    for (auto& c : run.v.clusters) {
      if (c.status != verify::ClusterStatus::certified) continue;
      Box within = c.certificate.box;  // room for a root that moved
      for (auto& w : within) w += Interval(-1e-6, 1e-6);
      const auto r = verify::coupled_loops_root(*perturbed.formulation, c.chart, c.certificate.box, within);
      CHECK_FALSE(r.proved);
      CHECK(r.how.find("every loop is rigid ('ring1', 'ring2')") != std::string::npos);
    }
    bool rejected = false;
    for (auto& f : verify::check_certificates(run.j, *perturbed.formulation).failures)
      rejected = rejected || f.find("the proof of its root through its loops does not hold") != std::string::npos;
    CHECK(rejected);
  }
}

TEST_CASE("bicyclohexane: a ring one bond length off its symmetry is not argued mobile", "[linkage][coupled]") {
  const std::string window = test::bicyclohexane_window(test::bicyclohexane_text(), test::bicyclohexane_pose('b'));
  const auto run = solve_window(window);
  REQUIRE(run.roots.size() == 2);
  const auto& c = run.v.clusters.at(run.v.clusters[0].status == verify::ClusterStatus::certified ? 0 : 1);
  REQUIRE(c.status == verify::ClusterStatus::certified);
  // Ring 2 with one bond 1e-9 longer is no longer mobile: at the same box the argument must
  // not take it for a loop on its curve (its pose may be gone; the search proves the window empty).
  std::string text = window;
  const std::string bond = "link = \"c7\",  a = 0, d = 1.526,";
  const size_t at = text.find(bond);
  REQUIRE(at != std::string::npos);
  text.replace(at, bond.size(), "link = \"c7\",  a = 0, d = 1.526000001,");
  const auto perturbed = formulate::load_case_text(text, "perturbed.toml");
  const Box start = perturbed.formulation->output_to_natural(c.chart, c.hull);
  const auto& sys = run.c.formulation->natural(c.chart);
  std::vector<model::Polynomial> sub;
  for (int e : c.subsystem) sub.push_back(sys.equations.at(e));
  const verify::CoupledRoom room = verify::coupled_room(sub, start, c.certificate);
  REQUIRE(room.unique);
  const auto r = verify::coupled_loops_root(*perturbed.formulation, c.chart, c.certificate.box, room.box);
  CHECK_FALSE(r.proved);
  CHECK(r.how.find("'ring2' is neither rigid in the box nor a symmetric six-joint loop") != std::string::npos);
  // The same call on the case as it is proves the root.
  CHECK(verify::coupled_loops_root(*run.c.formulation, c.chart, c.certificate.box, room.box).proved);
  CHECK(solve_window(text).roots.empty());
}

TEST_CASE("bicyclohexane: where no ring is rigid, the loops leave a curve, and say so", "[linkage][coupled]") {
  const auto loaded = formulate::load_case(test::src("cases/linkages/bicyclohexane.toml"));
  const auto& f = *loaded.formulation;
  // Both rings near boats (torsions i and i + 3 alike), 0.3 wide: neither ring's closure has
  // a unique root there, both rings being mobile.
  Box around;
  const auto names = f.output_names();
  auto pose = test::bicyclohexane_pose('b');
  const double w = test::chair_torsion();
  for (auto& [joint, at] : std::map<std::string, double>{{"c3-c4", 0}, {"c4-c5", -w}, {"c5-c6", w}, {"c6-c1", 0}})
    pose[joint] = at;
  for (auto& name : names) {
    const double at = pose.count(name) ? pose.at(name) : name == "c1-c2@ring2" ? -test::chair_torsion() : 2.0948;
    around.push_back(Interval(at - 0.3, at + 0.3));
  }
  const std::uint64_t chart = f.chart_for(around);
  const Box x = f.output_to_natural(chart, around);
  const auto r = verify::coupled_loops_root(f, chart, x, x);
  CHECK_FALSE(r.proved);
  CHECK(r.equations == 6);
  CHECK(r.unknowns == 7);
  CHECK(r.how.find("loops 'ring1', 'ring2' on their symmetric curves") != std::string::npos);
}
