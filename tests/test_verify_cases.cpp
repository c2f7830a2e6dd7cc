// Verification end to end on the bundled spherical cases: every cluster certified, roots
// pairwise disjoint, the headline exact, and the Agile Eye's trivial poses matching their
// closed-form rotations.
#include "formulate/load.hpp"
#include "solve/solve_case.hpp"
#include "verify/certify_case.hpp"
#include "verify/cluster.hpp"

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

TEST_CASE("clusters verified on several threads give the one-thread report", "[verify][cases]") {
  // The agile eye (many isolated roots) and the cyclohexane curve (crossings certified in a
  // sample first): every cluster's verdict, root and crossings, in the same order.
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
    const verify::VerifyReport b = verify::verify_case(*c.formulation, r, three);
    REQUIRE(a.clusters.size() > 2);
    REQUIRE(a.clusters.size() == b.clusters.size());
    CHECK(a.headline == b.headline);
    for (size_t k = 0; k < a.clusters.size(); ++k) {
      const auto &x = a.clusters[k], &y = b.clusters[k];
      CHECK(x.status == y.status);
      CHECK(x.reason == y.reason);
      CHECK(x.boxes == y.boxes);
      CHECK(x.duplicate_of == y.duplicate_of);
      CHECK(x.crossings_certified == y.crossings_certified);
      REQUIRE(x.root.size() == y.root.size());
      for (size_t d = 0; d < x.root.size(); ++d) {
        CHECK(x.root[d].lower() == y.root[d].lower());
        CHECK(x.root[d].upper() == y.root[d].upper());
      }
    }
  }
}
