// The symmetric loop (verify/symmetric_loop.hpp): its float R, which only steers float
// Newton, against its interval enclosures and its own difference quotients; D, A and A's
// Jacobians against the loop's transforms multiplied apart in double.
#include "formulate/linkage.hpp"
#include "formulate/load.hpp"
#include "verify/symmetric_loop.hpp"

#include <catch2/catch.hpp>

#include <Eigen/LU>

#include <random>

using namespace linkbox;

TEST_CASE("a symmetric loop's float R agrees with its enclosures and its difference quotients",
          "[verify][symmetric]") {
  const formulate::LoadedCase c = formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/cases/linkages/6r-mobile.toml");
  const auto loop = verify::SymmetricLoop::of(*c.formulation);
  REQUIRE(loop);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-3.0, 3.0);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Vector3d u(angle(rng), angle(rng), angle(rng));
    const Box at{Interval(u(0)), Interval(u(1)), Interval(u(2))};
    Eigen::Vector2d r;
    Eigen::Matrix<double, 2, 3> j;
    loop->r_at(u, r, j);
    const newton::IVector ri = loop->r_values(at);
    const newton::IMatrix ji = loop->r_jacobian(at);
    for (int i = 0; i < 2; ++i) {
      CHECK(std::fabs(r(i) - median(ri(i))) <= 1e-12 + width_up(ri(i)));
      for (int k = 0; k < 3; ++k) CHECK(std::fabs(j(i, k) - median(ji(i, k))) <= 1e-12 + width_up(ji(i, k)));
    }
    constexpr double h = 1e-6;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d up = u, down = u;
      up(k) += h;
      down(k) -= h;
      Eigen::Vector2d r_up, r_down;
      Eigen::Matrix<double, 2, 3> unused;
      loop->r_at(up, r_up, unused);
      loop->r_at(down, r_down, unused);
      for (int i = 0; i < 2; ++i) CHECK(std::fabs((r_up(i) - r_down(i)) / (2 * h) - j(i, k)) < 1e-6);
    }
  }
}

namespace {

// Entry i's transform Rz(theta) Tz(d) Tx(a) Rx(alpha) in plain double, built apart from
// SymmetricLoop's products.
Eigen::Matrix4d dh(double theta, double a, double d, double alpha) {
  Eigen::Matrix4d rz = Eigen::Matrix4d::Identity(), tz = rz, tx = rz, rx = rz;
  rz.topLeftCorner<2, 2>() << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
  tz(2, 3) = d;
  tx(0, 3) = a;
  rx.block<2, 2>(1, 1) << std::cos(alpha), -std::sin(alpha), std::sin(alpha), std::cos(alpha);
  return rz * tz * tx * rx;
}

}  // namespace

TEST_CASE("a symmetric loop's D and A enclose the loop's transforms computed apart", "[verify][symmetric]") {
  const formulate::LoadedCase c = formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/cases/linkages/6r-mobile.toml");
  const auto loop = verify::SymmetricLoop::of(*c.formulation);
  REQUIRE(loop);
  const auto* linkage = dynamic_cast<const formulate::LinkageFormulation*>(c.formulation.get());
  REQUIRE(linkage);
  const auto& links = linkage->linkage_case().loops.at(0).links;
  // T(theta_1..3) of the first three entries, whose parameters the last three repeat.
  auto transform = [&](const Eigen::Vector3d& theta) {
    Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
    for (int i = 0; i < 3; ++i)
      t *= dh(theta(i), median(links[i].a), median(links[i].d), median(links[i].alpha));
    return t;
  };
  auto a_float = [&](const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    const Eigen::Matrix4d plus = transform(u + v), minus = transform(u - v);
    return Eigen::Matrix4d(plus + plus.inverse() - minus - minus.inverse());
  };
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(-3.0, 3.0);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Vector3d u(angle(rng), angle(rng), angle(rng)), v(angle(rng), angle(rng), angle(rng));
    Box uv(6);
    for (int i = 0; i < 3; ++i) uv[i] = Interval(u(i)), uv[i + 3] = Interval(v(i));
    const Eigen::Matrix4d d = transform(u + v) - transform(u - v).inverse(), a = a_float(u, v);
    const newton::IVector di = loop->d_values(uv), ai = loop->a_values(uv);
    const newton::IMatrix jv = loop->a_jacobian_v(uv), ju = loop->a_jacobian_u(uv);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 4; ++j) {
        CHECK(std::fabs(d(i, j) - median(di(4 * i + j))) <= 1e-12 + width_up(di(4 * i + j)));
        CHECK(std::fabs(a(i, j) - median(ai(4 * i + j))) <= 1e-12 + width_up(ai(4 * i + j)));
      }
    constexpr double h = 1e-6;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(k);
      const Eigen::Matrix4d along_v = (a_float(u, v + e) - a_float(u, v - e)) / (2 * h);
      const Eigen::Matrix4d along_u = (a_float(u + e, v) - a_float(u - e, v)) / (2 * h);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) {
          CHECK(std::fabs(along_v(i, j) - median(jv(4 * i + j, k))) < 1e-6);
          CHECK(std::fabs(along_u(i, j) - median(ju(4 * i + j, k))) < 1e-6);
        }
    }
  }
}
