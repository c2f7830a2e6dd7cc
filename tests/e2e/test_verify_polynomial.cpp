// Verification outcomes that must never be over-claimed: a double root, a root on the edge
// of the domain, a box without roots, roots of overdetermined systems; and the exact
// statement when everything is proved.
#include "formulate/load.hpp"
#include "report/json.hpp"
#include "verify/check.hpp"
#include "solve/solve_case.hpp"
#include "verify/certify_case.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>

using namespace linkbox;

namespace {

verify::VerifyReport solve_text(const std::string& toml, const std::string& prune = "hc4,newton",
                                double sigma = 1e-6, verify::CheckOutcome* checked = nullptr) {
  formulate::LoadedCase c = formulate::load_case_text(toml, "inline.toml");
  solve::RunOptions o;
  o.progress = false;
  o.strategy.prune = solve::Strategy::parse(prune);
  o.params.sigma = sigma;
  auto r = solve::solve_case(*c.formulation, o);
  REQUIRE(r.complete);
  auto v = verify::verify_case(*c.formulation, r);
  if (checked) {
    nlohmann::json j = report::result_json(c.name, c.file, *c.formulation, o, r);
    report::add_verification(j, *c.formulation, v);
    *checked = verify::check_certificates(j, *c.formulation);
  }
  return v;
}

}  // namespace

TEST_CASE("circle and line: exactly two roots", "[verify][polynomial]") {
  auto v = solve_text(R"(kind = "polynomial"
name = "t"
variables = [ { name = "x", domain = [-2, 2] }, { name = "y", domain = [-2, 2] } ]
equations = [ "x^2 + y^2 - 1", "x - y" ])");
  CHECK(v.exact);
  CHECK(v.certified_roots == 2);
}

TEST_CASE("verification stops at its time limit or a second interrupt and says so", "[verify][polynomial]") {
  formulate::LoadedCase c = formulate::load_case_text(R"(kind = "polynomial"
name = "t"
variables = [ { name = "x", domain = [-2, 2] }, { name = "y", domain = [-2, 2] } ]
equations = [ "x^2 + y^2 - 1", "x - y" ])",
                                                      "inline.toml");
  solve::RunOptions o;
  o.progress = false;
  o.params.sigma = 1e-6;
  const auto r = solve::solve_case(*c.formulation, o);
  REQUIRE(r.complete);
  verify::VerifyOptions vo;
  vo.time_limit = 1e-12;  // spent before the first cluster
  const auto cut = verify::verify_case(*c.formulation, r, vo);
  CHECK(cut.timed_out);
  CHECK_FALSE(cut.exact);
  CHECK(cut.certified_roots == 0);
  REQUIRE(cut.clusters.size() == 2);
  for (auto& cl : cut.clusters) {
    CHECK(cl.status == verify::ClusterStatus::unverified);
    CHECK(cl.reason == "verification skipped (time limit)");
  }
  vo.time_limit = 600;
  vo.skip_rest = [] { return true; };  // a second interrupt, before the first cluster
  const auto skipped = verify::verify_case(*c.formulation, r, vo);
  CHECK_FALSE(skipped.exact);
  REQUIRE(skipped.clusters.size() == 2);
  for (auto& cl : skipped.clusters) CHECK(cl.reason == "verification skipped (interrupted)");
  vo.skip_rest = nullptr;
  const auto whole = verify::verify_case(*c.formulation, r, vo);
  CHECK_FALSE(whole.timed_out);
  CHECK(whole.exact);
  CHECK(whole.certified_roots == 2);
}

TEST_CASE("a double root is never certified", "[verify][polynomial]") {
  // The line y = 1 touches the circle at (0, 1).
  auto v = solve_text(R"(kind = "polynomial"
name = "t"
variables = [ { name = "x", domain = [-2, 2] }, { name = "y", domain = [-2, 2] } ]
equations = [ "x^2 + y^2 - 1", "y - 1" ])");
  CHECK(v.certified_roots == 0);
  CHECK_FALSE(v.exact);
  REQUIRE(v.unverified >= 1);
  for (auto& c : v.clusters)
    if (c.status == verify::ClusterStatus::unverified)
      CHECK((c.reason == "singular Jacobian" || c.reason == "inflation failed" ||
             c.reason.rfind("singular Jacobian in the cluster", 0) == 0));
}

TEST_CASE("a root on the edge of the domain is reported as such, not counted", "[verify][polynomial]") {
  // x^2 + y^2 = 1 with y = 0 has x = 1 on the domain's edge x <= 1, and x = -1 inside: the
  // edge root is the rational point (1, 0), in the domain exactly (verify/exact_point.hpp).
  verify::CheckOutcome checked;
  auto rational = solve_text(R"(kind = "polynomial"
name = "t"
variables = [ { name = "x", domain = [-2, 1] }, { name = "y", domain = [-1, 1] } ]
equations = [ "x^2 + y^2 - 1", "y" ])",
                             "hc4,newton", 1e-6, &checked);
  CHECK(rational.certified_roots == 2);
  CHECK(rational.exact);
  CHECK(checked.failures.empty());
  // x^2 + y^2 = 3 with y^2 = 2: the edge root (1, sqrt 2) is not rational, so nothing decides
  // its side; (-1, sqrt 2) is inside.
  auto v = solve_text(R"(kind = "polynomial"
name = "t"
variables = [ { name = "x", domain = [-2, 1] }, { name = "y", domain = [0, 2] } ]
equations = [ "x^2 + y^2 - 3", "y^2 - 2" ])");
  CHECK(v.certified_roots == 1);
  CHECK_FALSE(v.exact);
  int edge = 0;
  for (auto& c : v.clusters)
    if (c.status == verify::ClusterStatus::unverified) {
      CHECK(c.reason.find("domain boundary") != std::string::npos);
      CHECK(c.certificate.status == newton::Status::certified);  // it exists, just beyond doubt only near the edge
      ++edge;
    }
  CHECK(edge == 1);
}

TEST_CASE("no real root: the whole domain is proved empty", "[verify][polynomial]") {
  auto v = solve_text(R"(kind = "polynomial"
name = "t"
variables = [ { name = "x", domain = [-3, 3] }, { name = "y", domain = [-3, 3] } ]
equations = [ "x^2 + y^2 + 1", "x - y" ])");
  CHECK(v.exact);
  CHECK(v.certified_roots == 0);
  CHECK(v.headline == "exactly 0 roots in the domain, each in its certified box");
}

TEST_CASE("a polynomial case goes through the L/P/H path (safe and exact LP) and loses no planted root", "[verify][polynomial][lp]") {
  formulate::LoadedCase c = formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/cases/polynomial/planted-cubic.toml");
  const double r[3] = {-1, 0.5, 2};
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (auto backend : {prune::lp::LpBackend::safe, prune::lp::LpBackend::exact}) {
    solve::RunOptions o;
    o.progress = false;
    o.strategy.prune = solve::Strategy::parse("lp");
    o.strategy.lp = backend;
    o.params.sigma = 1e-3;
    auto res = solve::solve_case(*c.formulation, o);
    REQUIRE(res.complete);
    for (auto& p : perms) {
      int hits = 0;
      for (auto& s : res.subproblems)
        for (auto& b : s.solutions)
          hits += contains(b[0], r[p[0]]) && contains(b[1], r[p[1]]) && contains(b[2], r[p[2]]);
      INFO(prune::lp::to_string(backend));
      CHECK(hits >= 1);
    }
    auto v = verify::verify_case(*c.formulation, res);
    CHECK(v.certified_roots == 6);
    CHECK(v.exact);
  }
}

// Its roots +-(1/sqrt 2, 1/sqrt 2) are irrational, so no exact point makes the third equation
// vanish (a rational root is certified: "an overdetermined system's exact root" in
// test_classic_cases.cpp).
TEST_CASE("an overdetermined system: its irrational roots are consistent candidates, never certified",
          "[verify][polynomial]") {
  verify::CheckOutcome checked;
  auto v = solve_text(R"(kind = "polynomial"
name = "t"
variables = [ { name = "x", domain = [-2, 2] }, { name = "y", domain = [-2, 2] } ]
equations = [ "x - y", "x^2 + y^2 - 1", "x^4 + y^4 - 1/2" ])", {"hc4"}, 1e-6, &checked);
  CHECK(v.certified_roots == 0);
  CHECK_FALSE(v.exact);
  REQUIRE(v.unverified >= 2);
  const double r = std::sqrt(0.5);
  for (auto& c : v.clusters) {
    if (c.status != verify::ClusterStatus::unverified) continue;
    INFO(c.reason);
    CHECK(c.reason.rfind("overdetermined: 2 of 3 equations have a unique root in the box; the other 1 contains 0 there", 0) == 0);
    CHECK(c.subsystem.size() == 2);
    const double s = c.certificate.box[0].lower() > 0 ? r : -r;
    CHECK((contains(c.certificate.box[0], s) && contains(c.certificate.box[1], s)));
  }
  CHECK(v.headline.find("overdetermined: 2 of 3 equations have a unique root in the box") != std::string::npos);
  CHECK(checked.failures.empty());
  CHECK(checked.checked >= 1);
}

TEST_CASE("an overdetermined system with a curve of roots: crossings leave out the extra equations",
          "[verify][polynomial]") {
  // The unit circle in the plane z = 0, written with two more equations than a curve needs.
  verify::CheckOutcome checked;
  auto v = solve_text(R"(kind = "polynomial"
name = "t"
variables = [ { name = "x", domain = [-2, 2] }, { name = "y", domain = [-2, 2] }, { name = "z", domain = [-1, 1] } ]
equations = [ "x^2 + y^2 - 1", "z", "z*x", "z*y" ])", {"hc4"}, 0.05, &checked);
  CHECK(v.certified_roots == 0);
  CHECK(v.curves >= 1);
  for (auto& c : v.clusters) {
    if (c.status != verify::ClusterStatus::curve) continue;
    CHECK(2 * static_cast<size_t>(c.crossings_certified) >= c.crossings.size());
    for (auto& x : c.crossings)
      if (x.certificate.status == newton::Status::certified) CHECK(x.dropped_equations.size() == 2);
  }
  CHECK(checked.failures.empty());
  CHECK(checked.checked >= 1);
}
