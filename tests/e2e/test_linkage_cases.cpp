// The iterated-LP pipeline end to end on the paper's linkages, checked against independent
// computations: the DH forward kinematics in double (loop-closure residual of each root after
// a float Newton polish) and the cyclohexane chair angle from the bond geometry.
#include "formulate/load.hpp"
#include "solve/solve_case.hpp"
#include "verify/certify_case.hpp"
#include "verify/cluster.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

using namespace linkbox;

namespace {

struct Dh {
  double a, d, alpha;
};

Eigen::Matrix4d dh_product(const std::vector<Dh>& links, const Eigen::VectorXd& theta) {
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  for (size_t i = 0; i < links.size(); ++i) {
    Eigen::Matrix4d rz = Eigen::Matrix4d::Identity(), tz = Eigen::Matrix4d::Identity(),
                    tx = Eigen::Matrix4d::Identity(), rx = Eigen::Matrix4d::Identity();
    rz.block<3, 3>(0, 0) = Eigen::AngleAxisd(theta[i], Eigen::Vector3d::UnitZ()).toRotationMatrix();
    tz(2, 3) = links[i].d;
    tx(0, 3) = links[i].a;
    rx.block<3, 3>(0, 0) = Eigen::AngleAxisd(links[i].alpha, Eigen::Vector3d::UnitX()).toRotationMatrix();
    t = t * rz * tz * tx * rx;
  }
  return t;
}

// Residual of the closure: rotation part (3 independent entries) and translation.
Eigen::VectorXd closure(const std::vector<Dh>& links, const Eigen::VectorXd& theta) {
  const Eigen::Matrix4d t = dh_product(links, theta);
  Eigen::VectorXd r(6);
  r << t(2, 1) - t(1, 2), t(0, 2) - t(2, 0), t(1, 0) - t(0, 1), t(0, 3), t(1, 3), t(2, 3);
  return r;
}

// Float Newton (least squares, finite-difference Jacobian) from a box centre.
double polished_residual(const std::vector<Dh>& links, Eigen::VectorXd theta) {
  for (int it = 0; it < 30; ++it) {
    const Eigen::VectorXd f = closure(links, theta);
    Eigen::MatrixXd j(6, theta.size());
    for (int k = 0; k < theta.size(); ++k) {
      Eigen::VectorXd h = Eigen::VectorXd::Zero(theta.size());
      h[k] = 1e-7;
      j.col(k) = (closure(links, theta + h) - closure(links, theta - h)) / 2e-7;
    }
    theta -= j.completeOrthogonalDecomposition().solve(f);
  }
  return (dh_product(links, theta) - Eigen::Matrix4d::Identity()).norm();
}

std::string path(const std::string& p) { return std::string(LINKBOX_SOURCE_DIR) + "/" + p; }

}  // namespace

TEST_CASE("rigid 6R: 16 distinct poses, each a loop closure, certified and exact", "[linkage][cases][slow]") {
  formulate::LoadedCase c = formulate::load_case(path("cases/linkages/6r-rigid.toml"));
  solve::RunOptions o;
  o.progress = false;
  o.strategy.prune = solve::Strategy::parse("lp");
  auto r = solve::solve_case(*c.formulation, o);
  REQUIRE(r.complete);
  // Table I, first column (0.0175 as written).
  const std::vector<Dh> links = {{0.3, 0.0106, M_PI / 2}, {1, 0, 0.0175},      {0, 0.2, M_PI / 2},
                                 {1.5, 0, 0.0175},        {0, 0, M_PI / 2}, {1.1353, 0.1049, 1.4716}};
  auto v = verify::verify_case(*c.formulation, r);
  CHECK(v.certified_roots == 16);
  CHECK(v.exact);
  CHECK(v.headline == "exactly 16 roots in the domain, each in its certified box");
  std::vector<Box> roots;
  for (auto& cl : v.clusters) {
    if (cl.status != verify::ClusterStatus::certified || cl.duplicate_of >= 0) continue;
    roots.push_back(cl.root);
    Eigen::VectorXd theta(6);
    for (int i = 0; i < 6; ++i) theta[i] = median(cl.root[i]);
    CHECK(polished_residual(links, theta) < 1e-10);
    CHECK(max_width(cl.root) < 1e-9);
  }
  REQUIRE(roots.size() == 16);
  for (size_t i = 0; i < roots.size(); ++i)
    for (size_t k = 0; k < i; ++k) CHECK_FALSE(verify::boxes_touch(roots[i], roots[k], std::vector<bool>(6, true)));
  // Every solution box, polished from its centre, reaches a closed configuration too.
  for (auto& s : r.subproblems)
    for (auto& b : s.solutions) {
      Box out = c.formulation->to_output(s.index, b);
      Eigen::VectorXd theta(6);
      for (int i = 0; i < 6; ++i) theta[i] = median(out[i]);
      CHECK(polished_residual(links, theta) < 1e-10);
    }
}

TEST_CASE("cyclohexane: the chairs are certified roots inside solution boxes, the rest a curve", "[linkage][cases]") {
  formulate::LoadedCase c = formulate::load_case(path("cases/linkages/cyclohexane.toml"));
  solve::RunOptions o;
  o.progress = false;
  o.strategy.prune = solve::Strategy::parse("lp");
  o.params.sigma = 0.1;
  o.params.rho = 0.95;
  auto r = solve::solve_case(*c.formulation, o);
  REQUIRE(r.complete);
  // Chair: all torsions +-(w, -w, w, -w, w, -w). With bond angle pi - alpha, alternating
  // torsions close the ring when cos w = -cos(alpha') / (1 + cos(alpha')) for the bond angle
  // alpha' = pi - alpha (the classical chair relation), independent of the bond length.
  const double alpha = 1.23, bond = M_PI - alpha;
  const double w = std::acos(-std::cos(bond) / (1 + std::cos(bond)));
  const std::vector<Dh> links(6, Dh{0, 1.526, alpha});
  for (double sign : {1.0, -1.0}) {
    Eigen::VectorXd chair(6);
    for (int i = 0; i < 6; ++i) chair[i] = sign * (i % 2 ? -w : w);
    REQUIRE((dh_product(links, chair) - Eigen::Matrix4d::Identity()).norm() < 1e-12);  // the closed form holds
    int in_box = 0;
    for (auto& s : r.subproblems)
      for (auto& b : s.solutions) {
        Box out = c.formulation->to_output(s.index, b);
        bool inside = true;
        for (int i = 0; i < 6; ++i) inside = inside && contains(out[i], chair[i]);
        in_box += inside;
      }
    CHECK(in_box >= 1);
  }
  auto v = verify::verify_case(*c.formulation, r);
  CHECK(v.certified_roots == 2);
  CHECK(v.curves >= 1);
  CHECK_FALSE(v.exact);
  for (auto& cl : v.clusters) {
    if (cl.status == verify::ClusterStatus::certified)
      for (int i = 0; i < 6; ++i) CHECK(std::abs(std::abs(median(cl.root[i])) - w) < 1e-9);
    if (cl.status == verify::ClusterStatus::curve) CHECK(2 * static_cast<size_t>(cl.crossings_certified) > cl.crossings.size());
  }
}

namespace {

// Whether x, modulo 2 pi, lies within `margin` of the interval.
bool near_angle(const Interval& box, double x, double margin) {
  for (int k = -2; k <= 2; ++k) {
    const double y = x + 2 * M_PI * k;
    if (box.lower() - margin <= y && y <= box.upper() + margin) return true;
  }
  return false;
}

bool near_box(const Box& out, const Eigen::Vector4d& theta, double margin) {
  for (int i = 0; i < 4; ++i)
    if (!near_angle(out[i], theta[i], margin)) return false;
  return true;
}

// Bennett's closed form: theta3 = -theta1, theta4 = -theta2, tan(theta1/2) tan(theta2/2) = sqrt 3.
Eigen::Vector4d bennett_point(double theta1) {
  const double theta2 = 2 * std::atan2(std::sqrt(3.0), std::tan(theta1 / 2));
  return {theta1, theta2, -theta1, -theta2};
}

}  // namespace

TEST_CASE("Bennett 4R: the solution boxes cover its closed-form curve and nothing else", "[linkage][cases][map]") {
  formulate::LoadedCase c = formulate::load_case(path("cases/linkages/bennett.toml"));
  const std::vector<Dh> links = {{1, 0, M_PI / 6}, {2, 0, M_PI / 2}, {1, 0, M_PI / 6}, {2, 0, M_PI / 2}};
  for (const char* prune : {"auto", "lp", "hc4,newton"}) {
    CAPTURE(prune);
    solve::RunOptions o;
    o.progress = false;
    o.strategy.prune = solve::Strategy::parse(prune);
    o.params.sigma = 0.1;  // the case's
    auto r = solve::solve_case(*c.formulation, o);
    REQUIRE(r.complete);
    std::vector<Box> outs;
    for (auto& s : r.subproblems)
      for (auto& b : s.solutions) outs.push_back(c.formulation->to_output(s.index, b));
    REQUIRE(!outs.empty());
    // Every point of the curve is in a solution box (none was discarded) ...
    for (int k = 0; k < 720; ++k) {
      const Eigen::Vector4d theta = bennett_point(-M_PI + (k + 0.5) * 2 * M_PI / 720);
      REQUIRE((dh_product(links, theta) - Eigen::Matrix4d::Identity()).norm() < 1e-12);  // it closes the loop
      CHECK(std::any_of(outs.begin(), outs.end(), [&](const Box& b) { return near_box(b, theta, 1e-9); }));
    }
    // ... and every box is within its own width of the curve (no isolated pose elsewhere).
    for (const Box& b : outs) {
      bool near = false;
      for (int k = 0; k < 4000 && !near; ++k) near = near_box(b, bennett_point(-M_PI + k * 2 * M_PI / 4000), max_width(b));
      CHECK(near);
    }
    auto v = verify::verify_case(*c.formulation, r);
    CHECK(v.certified_roots == 0);
    for (auto& cl : v.clusters)
      if (cl.map && cl.map->proved) CHECK(cl.map->components.size() == 1);
  }
}
