// A system that separates into blocks (model/block_triangular.hpp), as geometric constraint
// problems do: a chain of circle intersections where each pair of points is fixed by the
// pair before it. The search splits the first open block first, Newton falls back to the
// regular blocks where the whole midpoint Jacobian is singular, and the lifted sums
// (x4 - x1)^2 are substituted out of Newton; every root is found, certified and counted.
#include "tests/solved_case.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <vector>

using namespace linkbox;

namespace {

using Point = std::array<double, 2>;

// The two points at distance r1 from c1 and r2 from c2 (closed form, in double).
std::vector<Point> meet(Point c1, double r1, Point c2, double r2) {
  const double dx = c2[0] - c1[0], dy = c2[1] - c1[1], d = std::hypot(dx, dy);
  const double a = (r1 * r1 - r2 * r2 + d * d) / (2 * d), h = std::sqrt(r1 * r1 - a * a);
  const Point m{c1[0] + a * dx / d, c1[1] + a * dy / d};
  return {{m[0] - h * dy / d, m[1] + h * dx / d}, {m[0] + h * dy / d, m[1] - h * dx / d}};
}

}  // namespace

TEST_CASE("a chain of circle intersections: every root of every block, certified", "[decomposed]") {
  const std::string bch = R"~(Variables
  x1 in [-1e8, 1e8];
  y1 in [-1e8, 1e8];
  x4 in [-1e8, 1e8];
  y4 in [-1e8, 1e8];
  x5 in [-1e8, 1e8];
  y5 in [-1e8, 1e8];
Constraints
  (x1-2)^2 + y1^2 = 16;
  (x4-x1)^2 + (y4-y1)^2 = 16;
  (x4-2)^2 + y4^2 = 25;
  (x4-x5)^2 + (y4-y5)^2 = 16;
  (x5-2)^2 + y5^2 = 9;
  (x5-5)^2 + y5^2 = 18;
end
)~";
  std::vector<std::array<double, 6>> expected;  // x1, y1, x4, y4, x5, y5
  for (const Point& p5 : meet({2, 0}, 3, {5, 0}, std::sqrt(18.0)))
    for (const Point& p4 : meet({2, 0}, 5, p5, 4))
      for (const Point& p1 : meet({2, 0}, 4, p4, 4)) expected.push_back({p1[0], p1[1], p4[0], p4[1], p5[0], p5[1]});
  REQUIRE(expected.size() == 8);
  for (const char* prune : {"hc4,newton", "auto"}) {
    INFO(prune);
    const test::SolvedCase run = test::solve_loaded(formulate::load_case_text(bch, "chain.bch"), prune, 1e-6);
    CHECK(run.v.exact);
    REQUIRE(run.roots.size() == 8);
    for (const auto& e : expected) {
      int found = 0;
      for (const Box& r : run.roots) {
        bool near = true;
        for (int i = 0; i < 6; ++i) near = near && std::fabs(median(r[i]) - e[i]) < 1e-9;
        found += near;
      }
      CHECK(found == 1);
    }
  }
}
