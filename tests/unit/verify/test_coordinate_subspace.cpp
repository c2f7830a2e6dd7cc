// Redundant systems mapped through a coordinate hyperplane (verify/coordinate_subspace.hpp):
// the structure is found exactly, and the span test holds only where the rest has an arc.
#include "verify/coordinate_subspace.hpp"

#include <catch2/catch.hpp>

using namespace linkbox;
using model::Polynomial;

namespace {

Polynomial v(int i) { return Polynomial::variable(i); }
Polynomial c(double x) { return Polynomial::constant(Interval(x)); }

// z (x - 1/2), z (y - 1/2), x^2 + y^2 + z - 1 over (x, y, z).
std::vector<Polynomial> circle_on_plane(double offset = 0) {
  return {v(2) * (v(0) - c(0.5)) + c(offset), v(2) * (v(1) - c(0.5)), v(0) * v(0) + v(1) * v(1) + v(2) - c(1)};
}

}  // namespace

TEST_CASE("the hyperplane where the surplus equations vanish is found exactly", "[verify][subspace]") {
  const auto s = verify::coordinate_subspace(circle_on_plane(), 3);
  REQUIRE(s);
  CHECK(s->variable == 2);
  CHECK(s->vanishing == std::vector<int>{0, 1});
  CHECK(s->rest == std::vector<int>{2});
  CHECK(verify::dropped_for(*s, 0) == std::vector<int>{1});
  // A constant term, however small, and a square system have none.
  CHECK_FALSE(verify::coordinate_subspace(circle_on_plane(1e-12), 3));
  auto square = circle_on_plane();
  square.pop_back();
  CHECK_FALSE(verify::coordinate_subspace(square, 3));
}

TEST_CASE("the rest spans a box only across its arc's parameter, with the plane inside", "[verify][subspace]") {
  const auto s = verify::coordinate_subspace(circle_on_plane(), 3);
  REQUIRE(s);
  // Around (cos 0.3, sin 0.3, 0): the circle is a graph over y there.
  const double x = std::cos(0.3), y = std::sin(0.3);
  const Box box{Interval(x - 0.05, x + 0.05), Interval(y - 0.01, y + 0.01), Interval(-0.01, 0.01)};
  CHECK(verify::spans_on_subspace(*s, box, 1));
  CHECK_FALSE(verify::spans_on_subspace(*s, box, 2));  // the plane's own side
  Box above = box;
  above[2] = Interval(0.01, 0.02);  // misses z = 0
  CHECK_FALSE(verify::spans_on_subspace(*s, above, 1));
  Box beside = box;
  beside[0] = Interval(x + 0.2, x + 0.3);  // the circle does not cross it
  CHECK_FALSE(verify::spans_on_subspace(*s, beside, 1));
}
