// End-to-end on the bundled spherical cases, against answers computed independently:
// closed-form ZXZ Euler angles for the wrist, a multi-start Newton on the rotation
// constraints (R v_i) . w_i = 0 for the Agile Eye.
#include "formulate/spherical.hpp"
#include "formulate/load.hpp"
#include "solve/solve_case.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <cmath>
#include <random>

using namespace linkbox;

namespace {

std::string case_path(const std::string& name) { return std::string(LINKBOX_SOURCE_DIR) + "/cases/spherical/" + name; }

struct Solved {
  formulate::LoadedCase c;
  solve::CaseResult r;
};

Solved solve_bundled(const std::string& name) {
  Solved s{formulate::load_case(case_path(name)), {}};
  solve::RunOptions o;
  o.progress = false;
  s.r = solve::solve_case(*s.c.formulation, o);
  return s;
}

double angle_distance(double a, double b) {
  double d = std::fmod(std::abs(a - b), 2 * M_PI);
  return std::min(d, 2 * M_PI - d);
}

// Distance from a point to an interval, modulo 2 pi.
double distance_to(const Interval& x, double v) {
  if (contains(x, v)) return 0;
  double lo = angle_distance(x.lower(), v), hi = angle_distance(x.upper(), v);
  // Inside modulo 2 pi?
  for (int k = -1; k <= 1; ++k)
    if (contains(x, v + 2 * M_PI * k)) return 0;
  return std::min(lo, hi);
}

Eigen::Matrix3d rotation(const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

}  // namespace

TEST_CASE("wrist: both closed-form ZXZ solutions are enclosed and nothing else", "[spherical][cases]") {
  Solved s = solve_bundled("wrist.toml");
  REQUIRE(s.r.complete);
  const Eigen::Quaterniond q0(0.019630402526971728, 0.09842416798574144, 0.65958471434624844, -0.7448995469549714);
  const Eigen::Matrix3d R = q0.normalized().toRotationMatrix();
  // R = Rz(p1) Rx(p2) Rz(p3): R(2,2) = cos p2, R(0,2) = s1 s2, R(1,2) = -c1 s2, R(2,0) = s2 s3, R(2,1) = s2 c3.
  std::vector<std::array<double, 3>> expected;
  for (double sign : {1.0, -1.0}) {
    double p2 = sign * std::acos(R(2, 2));
    double s2 = std::sin(p2);
    expected.push_back({std::atan2(R(0, 2) / s2, -R(1, 2) / s2), p2, std::atan2(R(2, 0) / s2, R(2, 1) / s2)});
  }
  for (auto& e : expected) {  // sanity of the closed form itself
    Eigen::Matrix3d M = rotation({0, 0, 1}, e[0]) * rotation({1, 0, 0}, e[1]) * rotation({0, 0, 1}, e[2]);
    REQUIRE((M - R).norm() < 1e-12);
  }
  std::vector<int> hits(expected.size(), 0);
  int boxes = 0;
  for (auto& sub : s.r.subproblems)
    for (auto& b : sub.solutions) {
      ++boxes;
      Box out = s.c.formulation->to_output(sub.index, b);
      int matched = 0;
      for (size_t k = 0; k < expected.size(); ++k) {
        double d = 0;
        for (int j = 0; j < 3; ++j) d = std::max(d, distance_to(out[j], expected[k][j]));
        if (d < 1e-9) ++hits[k], ++matched;
      }
      CHECK(matched == 1);  // every solution box holds one of the two solutions
    }
  CHECK(boxes >= 2);
  CHECK(hits[0] >= 1);
  CHECK(hits[1] >= 1);
}

TEST_CASE("agile eye: every forward-kinematics pose is found, the four trivial ones included", "[spherical][cases]") {
  Solved s = solve_bundled("agile-eye.toml");
  REQUIRE(s.r.complete);
  const Eigen::Vector3d u[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const Eigen::Vector3d w0[3] = {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}};
  const Eigen::Vector3d v[3] = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}};
  const double theta[3] = {2 * std::atan(1.0 / 5), 2 * std::atan(-1.0 / 3), 2 * std::atan(2.0 / 7)};
  Eigen::Vector3d w[3];
  for (int i = 0; i < 3; ++i) w[i] = rotation(u[i], theta[i]) * w0[i];

  // Independent method: Newton on F(q) = ((R(q) v_i) . w_i, |q|^2 - 1) from many starts.
  auto F = [&](const Eigen::Vector4d& q) {
    Eigen::Quaterniond Q(q[0], q[1], q[2], q[3]);
    Eigen::Matrix3d R = Q.toRotationMatrix();  // assumes unit q; |q|=1 is the 4th equation
    Eigen::Vector4d f;
    for (int i = 0; i < 3; ++i) f[i] = (R * v[i]).dot(w[i]);
    f[3] = q.squaredNorm() - 1;
    return f;
  };
  std::vector<Eigen::Matrix3d> poses;
  std::mt19937 rng(3);
  std::normal_distribution<double> n01;
  for (int start = 0; start < 3000; ++start) {
    Eigen::Vector4d q(n01(rng), n01(rng), n01(rng), n01(rng));
    q.normalize();
    for (int it = 0; it < 50; ++it) {
      Eigen::Matrix4d J;
      Eigen::Vector4d f = F(q);
      for (int k = 0; k < 4; ++k) {
        Eigen::Vector4d h = Eigen::Vector4d::Zero();
        h[k] = 1e-7;
        J.col(k) = (F(q + h) - F(q - h)) / 2e-7;
      }
      q -= J.fullPivLu().solve(f);
    }
    if (F(q).norm() > 1e-12) continue;
    Eigen::Matrix3d R = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
    bool known = false;
    for (auto& P : poses) known = known || (P - R).norm() < 1e-6;
    if (!known) poses.push_back(R);
  }
  // The trivial poses R v_i = s_i u_i with s1 s2 s3 = +1.
  int trivial = 0;
  for (auto& P : poses) {
    bool aligned = true;
    for (int i = 0; i < 3; ++i) aligned = aligned && std::abs(std::abs((P * v[i]).dot(u[i])) - 1) < 1e-9;
    trivial += aligned;
  }
  REQUIRE(trivial == 4);
  INFO("poses found by Newton: " << poses.size());

  // Every pose lies in the rotation output of some solution box, and every solution box's
  // rotation encloses (within its width) one of the poses.
  std::vector<int> hits(poses.size(), 0);
  for (auto& sub : s.r.subproblems)
    for (auto& b : sub.solutions) {
      auto outputs = s.c.formulation->declared_outputs(sub.index, b);
      REQUIRE(outputs.size() == 1);
      auto& M = outputs[0].rows;
      int matched = 0;
      for (size_t k = 0; k < poses.size(); ++k) {
        bool inside = true;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            inside = inside && M[i][j].lower() - 1e-9 <= poses[k](i, j) && poses[k](i, j) <= M[i][j].upper() + 1e-9;
        if (inside) ++hits[k], ++matched;
      }
      CHECK(matched == 1);
    }
  for (size_t k = 0; k < poses.size(); ++k) CHECK(hits[k] >= 1);
  CHECK(poses.size() >= 4);
}

TEST_CASE("search limits return partial results marked incomplete", "[solve]") {
  formulate::LoadedCase c = formulate::load_case(case_path("agile-eye.toml"));
  solve::RunOptions o;
  o.progress = false;
  o.params.max_boxes = 50;
  auto r = solve::solve_case(*c.formulation, o);
  CHECK_FALSE(r.complete);
  CHECK(r.stop_reason == "box limit reached");
  CHECK(r.total.processed <= 50);
}

TEST_CASE("same case, parameters and threads give the same boxes", "[solve]") {
  formulate::LoadedCase c = formulate::load_case(case_path("agile-eye.toml"));
  solve::RunOptions o;
  o.progress = false;
  o.threads = 2;
  auto a = solve::solve_case(*c.formulation, o), b = solve::solve_case(*c.formulation, o);
  o.threads = 1;
  auto d = solve::solve_case(*c.formulation, o);
  REQUIRE(a.subproblems.size() == b.subproblems.size());
  for (size_t i = 0; i < a.subproblems.size(); ++i) {
    REQUIRE(a.subproblems[i].solutions.size() == b.subproblems[i].solutions.size());
    REQUIRE(a.subproblems[i].solutions.size() == d.subproblems[i].solutions.size());
    for (size_t k = 0; k < a.subproblems[i].solutions.size(); ++k)
      for (size_t j = 0; j < a.subproblems[i].solutions[k].size(); ++j) {
        CHECK(equal(a.subproblems[i].solutions[k][j], b.subproblems[i].solutions[k][j]));
        CHECK(equal(a.subproblems[i].solutions[k][j], d.subproblems[i].solutions[k][j]));
      }
  }
}
