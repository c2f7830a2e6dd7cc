// Verification end to end on the bundled spherical cases: every cluster certified, roots
// pairwise disjoint, the headline exact, and the Agile Eye's trivial poses matching their
// closed-form rotations.
#include "formulate/load.hpp"
#include "solve/solve_case.hpp"
#include "verify/certify_case.hpp"
#include "verify/cluster.hpp"
#include "verify/cluster_json.hpp"

#include <nlohmann/json.hpp>

#include <catch2/catch.hpp>

using namespace linkbox;

namespace {

struct Verified {
  formulate::LoadedCase c;
  solve::CaseResult r;
  verify::VerifyReport v;
};

Verified verify_bundled(const std::string& path) {
  Verified s{formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/" + path), {}, {}};
  solve::RunOptions o;
  o.progress = false;
  s.r = solve::solve_case(*s.c.formulation, o);
  s.v = verify::verify_case(*s.c.formulation, s.r);
  return s;
}

std::vector<const verify::ClusterReport*> distinct_roots(const verify::VerifyReport& v) {
  std::vector<const verify::ClusterReport*> r;
  for (auto& c : v.clusters)
    if (c.status == verify::ClusterStatus::certified && c.duplicate_of < 0) r.push_back(&c);
  return r;
}

}  // namespace

TEST_CASE("wrist: exactly 2 certified roots, tight boxes", "[verify][cases]") {
  Verified s = verify_bundled("cases/spherical/wrist.toml");
  CHECK(s.v.certified_roots == 2);
  CHECK(s.v.exact);
  CHECK(s.v.headline == "exactly 2 roots in the domain, each in its certified box");
  for (auto* c : distinct_roots(s.v)) {
    CHECK(max_width(c->certificate.box) < 1e-12);
    CHECK(newton::recheck(s.c.formulation->natural_system(c->chart).equations, c->certificate));
  }
}

TEST_CASE("agile eye: every pose certified, the trivial ones with their closed-form rotation", "[verify][cases]") {
  Verified s = verify_bundled("cases/spherical/agile-eye.toml");
  CHECK(s.v.exact);
  auto roots = distinct_roots(s.v);
  CHECK(roots.size() == static_cast<size_t>(s.v.certified_roots));
  CHECK(s.v.certified_roots == 8);
  // Pairwise disjoint root boxes (angles modulo 2 pi).
  for (size_t i = 0; i < roots.size(); ++i)
    for (size_t k = 0; k < i; ++k) CHECK_FALSE(verify::boxes_touch(roots[i]->root, roots[k]->root, std::vector<bool>(6, true)));
  // Trivial poses: R v1 = s1 x, R v2 = s2 y, R v3 = s3 z with v = (z, x, y), s1 s2 s3 = 1:
  // R = [[0, 0, s1], [s2, 0, 0], [0, s3, 0]].
  int trivial = 0;
  for (auto* c : roots) {
    REQUIRE(c->outputs.size() == 1);
    const auto& R = c->outputs[0].rows;
    const double s1 = median(R[0][2]), s2 = median(R[1][0]), s3 = median(R[2][1]);
    if (std::abs(std::abs(s1) - 1) > 1e-6) continue;
    ++trivial;
    const double expected[3][3] = {{0, 0, s1}, {s2, 0, 0}, {0, s3, 0}};
    CHECK(s1 * s2 * s3 == Approx(1));
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        CHECK(contains(R[i][j], expected[i][j]));
        CHECK(width(R[i][j]) < 1e-9);
      }
  }
  CHECK(trivial == 4);
}

namespace {

void same_bits(const Box& a, const Box& b) {
  REQUIRE(a.size() == b.size());
  for (size_t d = 0; d < a.size(); ++d) {
    CHECK(a[d].lower() == b[d].lower());
    CHECK(a[d].upper() == b[d].upper());
  }
}

void same_certificate(const newton::Certificate& a, const newton::Certificate& b) {
  CHECK(a.status == b.status);
  CHECK(a.reason == b.reason);
  same_bits(a.box, b.box);
  same_bits(a.image, b.image);
  CHECK(a.preconditioner == b.preconditioner);
  CHECK(a.point == b.point);
  CHECK(a.unique_in_hull == b.unique_in_hull);
  CHECK(a.root_in_domain == b.root_in_domain);
}

// Field by field (not through report_json, so a field the JSON forgot would show).
void same_report(const verify::VerifyReport& a, const verify::VerifyReport& b) {
  REQUIRE(a.clusters.size() == b.clusters.size());
  CHECK(a.headline == b.headline);
  CHECK(a.certified_roots == b.certified_roots);
  for (size_t k = 0; k < a.clusters.size(); ++k) {
    const auto &x = a.clusters[k], &y = b.clusters[k];
    CHECK(x.status == y.status);
    CHECK(x.reason == y.reason);
    CHECK(x.boxes == y.boxes);
    CHECK(x.chart == y.chart);
    CHECK(x.duplicate_of == y.duplicate_of);
    CHECK(x.crossings_certified == y.crossings_certified);
    CHECK(x.max_residual == y.max_residual);
    CHECK(x.distances == y.distances);
    CHECK(x.subsystem == y.subsystem);
    CHECK(x.straddled == y.straddled);
    same_bits(x.hull, y.hull);
    same_bits(x.root, y.root);
    same_certificate(x.certificate, y.certificate);
    REQUIRE(x.outputs.size() == y.outputs.size());
    for (size_t m = 0; m < x.outputs.size(); ++m) {
      CHECK(x.outputs[m].name == y.outputs[m].name);
      REQUIRE(x.outputs[m].rows.size() == y.outputs[m].rows.size());
      for (size_t r = 0; r < x.outputs[m].rows.size(); ++r) same_bits(x.outputs[m].rows[r], y.outputs[m].rows[r]);
    }
    REQUIRE(x.crossings.size() == y.crossings.size());
    for (size_t c = 0; c < x.crossings.size(); ++c) {
      CHECK(x.crossings[c].box == y.crossings[c].box);
      CHECK(x.crossings[c].dropped_equations == y.crossings[c].dropped_equations);
      same_certificate(x.crossings[c].certificate, y.crossings[c].certificate);
    }
  }
}

}  // namespace

TEST_CASE("clusters verified on several threads, or elsewhere and sent back as JSON, give the one-thread report",
          "[verify][cases]") {
  // The agile eye (many isolated roots) and the cyclohexane curve (crossings certified in a
  // sample first): every cluster's verdict, root, certificate and crossings, in the same order.
  for (const char* path : {"cases/spherical/agile-eye.toml", "cases/linkages/cyclohexane.toml"}) {
    INFO(path);
    const formulate::LoadedCase c = formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/" + path);
    solve::RunOptions o;
    o.progress = false;
    o.params.sigma = 0.1;
    const solve::CaseResult r = solve::solve_case(*c.formulation, o);
    verify::VerifyOptions one, three;
    three.threads = 3;
    const verify::VerifyReport a = verify::verify_case(*c.formulation, r, one);
    REQUIRE(a.clusters.size() > 2);
    same_report(a, verify::verify_case(*c.formulation, r, three));
    // As distributed/ does it: each task and its report through JSON text.
    std::vector<verify::ClusterReport> sent;
    for (auto& t : verify::cluster_tasks(*c.formulation, r)) {
      const auto task = verify::task_from(nlohmann::json::parse(verify::task_json(t).dump()));
      const auto report = verify::verify_cluster(*c.formulation, task, one);
      sent.push_back(verify::report_from(nlohmann::json::parse(verify::report_json(report).dump())));
    }
    same_report(a, verify::conclude(*c.formulation, std::move(sent), r, one));
  }
}

TEST_CASE("cluster JSON keeps infinities and refuses malformed reports", "[verify]") {
  verify::ClusterReport c;
  c.hull = {Interval(-INFINITY, 1.0), Interval(0.1, INFINITY)};
  c.max_residual = INFINITY;
  c.certificate.preconditioner = Eigen::MatrixXd::Identity(2, 3) * 0.1;
  const nlohmann::json j = verify::report_json(c);
  const verify::ClusterReport back = verify::report_from(nlohmann::json::parse(j.dump()));
  same_bits(back.hull, c.hull);
  CHECK(back.max_residual == INFINITY);
  CHECK(back.certificate.preconditioner == c.certificate.preconditioner);
  nlohmann::json bad = j;
  bad["status"] = 9;
  CHECK_THROWS_AS(verify::report_from(bad), std::invalid_argument);
  bad = j;
  bad["certificate"]["preconditioner"][0] = 3;
  CHECK_THROWS_AS(verify::report_from(bad), std::invalid_argument);
  bad = j;
  bad["hull"][0] = {2.0, 1.0};
  CHECK_THROWS_AS(verify::report_from(bad), std::invalid_argument);
}
