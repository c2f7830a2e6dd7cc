// The symmetric loop's float R (verify/symmetric_loop.hpp, r_at), which only steers float
// Newton, against its interval enclosures and its own difference quotients.
#include "formulate/load.hpp"
#include "verify/symmetric_loop.hpp"

#include <catch2/catch.hpp>

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
