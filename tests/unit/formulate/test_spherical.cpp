// The quaternion loop expansion (spherical paper, Section 2) against direct products of
// rotations, and the wrist's eq. (5).
#include "formulate/spherical.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace linkbox;
using namespace linkbox::formulate;
using namespace linkbox::input;

namespace {

using Q = std::array<double, 4>;
Q mul(const Q& a, const Q& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}
Q rot(std::array<double, 3> p, double phi) {
  double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), s = std::sin(phi / 2);
  return {std::cos(phi / 2), s * p[0] / n, s * p[1] / n, s * p[2] / n};
}
Vec3 vec(std::array<double, 3> p) { return {Interval(p[0]), Interval(p[1]), Interval(p[2])}; }
Factor joint(int j, std::array<double, 3> axis) {
  Factor f;
  f.kind = Factor::Kind::joint;
  f.joint = j;
  f.axis = vec(axis);
  return f;
}

}  // namespace

TEST_CASE("loop expansion equals the direct product of rotations", "[spherical]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1), ang(-3.1, 3.1);
  for (int trial = 0; trial < 200; ++trial) {
    const int r = 1 + trial % 5;
    SphericalCase c;
    c.file = "test";
    for (int j = 0; j < r; ++j) c.joints.push_back({"j" + std::to_string(j), 1});
    Loop loop;
    loop.name = "L";
    std::vector<std::array<double, 3>> axes;
    std::vector<Q> fixed;
    for (int j = 0; j < r; ++j) {
      axes.push_back({u(rng), u(rng), u(rng) + 1.5});
      loop.factors.push_back(joint(j, axes.back()));
      // A fixed rotation after every other joint.
      if (j % 2 == 0) {
        Factor f;
        f.kind = Factor::Kind::fixed_rotation;
        std::array<double, 3> a{u(rng), 1.0, u(rng)};
        double angle = ang(rng);
        f.axis = vec(a);
        f.angle = Interval(angle);
        loop.factors.push_back(f);
        fixed.push_back(rot(a, angle));
      }
    }
    c.loops.push_back(loop);
    SphericalFormulation form(c);
    const size_t shift = rng() % (size_t{1} << r);
    auto eqs = form.loop_equations(0, shift);
    std::vector<double> phi(r);
    Box t(r);
    double scale = 1;
    for (int j = 0; j < r; ++j) {
      phi[j] = ang(rng) / 2;  // within the sub-problem range [-pi/2, pi/2]
      t[j] = Interval(std::tan(phi[j] / 2));
      scale *= std::sqrt(1 + std::tan(phi[j] / 2) * std::tan(phi[j] / 2));
    }
    Q direct{1, 0, 0, 0};
    size_t k = 0;
    for (int j = 0; j < r; ++j) {
      direct = mul(direct, rot(axes[j], phi[j] + ((shift >> j & 1) ? M_PI : 0.0)));
      if (j % 2 == 0) direct = mul(direct, fixed[k++]);
    }
    for (int comp = 0; comp < 3; ++comp)
      CHECK(median(eqs[comp].eval(t)) == Approx(scale * direct[comp + 1]).margin(1e-9));
  }
}

TEST_CASE("wrist expansion reproduces eq. (5) of the spherical paper", "[spherical]") {
  // q0^{-1} = e0 + e1 i + e2 j + e3 k with arbitrary e (the check is symbolic).
  const double e0 = 0.3, e1 = -0.5, e2 = 0.7, e3 = 0.2;
  SphericalCase c;
  c.file = "test";
  c.joints = {{"phi1", 1}, {"phi2", 1}, {"phi3", 1}};
  Loop loop;
  loop.name = "wrist";
  loop.factors = {joint(0, {0, 0, 1}), joint(1, {1, 0, 0}), joint(2, {0, 0, 1})};
  Factor q;
  q.kind = Factor::Kind::constant;
  q.q = {Interval(e0), Interval(e1), Interval(e2), Interval(e3)};
  loop.factors.push_back(q);
  c.loops.push_back(loop);
  SphericalFormulation form(c);
  auto eqs = form.loop_equations(0, 0);
  // Rows of eq. (5); columns: 1, t1, t2, t3, t1t2, t1t3, t2t3, t1t2t3.
  const double M[3][8] = {{e1, -e2, e0, -e2, e3, -e1, -e3, e0},
                          {e2, e1, -e3, e1, e0, -e2, -e0, -e3},
                          {e3, e0, e2, e0, -e1, -e3, e1, e2}};
  const std::vector<std::vector<int>> monomials = {{}, {0}, {1}, {2}, {0, 1}, {0, 2}, {1, 2}, {0, 1, 2}};
  for (int row = 0; row < 3; ++row) {
    std::map<model::Powers, double> expected;
    for (int col = 0; col < 8; ++col) {
      model::Powers p;
      for (int v : monomials[col]) p.emplace_back(v, 1);
      expected[p] = M[row][col];
    }
    for (auto& [p, coef] : eqs[row].terms()) {
      INFO("row " << row);
      REQUIRE(expected.count(p));
      CHECK(contains(coef, expected[p]));
      CHECK(width(coef) < 1e-15);
    }
    CHECK(eqs[row].terms().size() == 8);
  }
}

TEST_CASE("spherical formulation validates its case", "[spherical]") {
  SphericalCase c;
  c.file = "f.toml";
  c.joints = {{"a", 3}, {"b", 4}};
  Loop loop;
  loop.name = "L";
  loop.factors = {joint(0, {0, 0, 1}), joint(0, {1, 0, 0})};
  c.loops = {loop};
  CHECK_THROWS_WITH(SphericalFormulation(c), Catch::Contains("appears twice"));
  c.loops[0].factors = {joint(0, {0, 0, 1})};
  CHECK_THROWS_WITH(SphericalFormulation(c), Catch::Contains("f.toml:4: joint 'b' is used in no loop"));
  c.loops[0].factors = {joint(0, {0, 0, 0}), joint(1, {1, 0, 0})};
  CHECK_THROWS_WITH(SphericalFormulation(c), Catch::Contains("axis of zero length"));
}
