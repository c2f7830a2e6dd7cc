// Singular points of curves (verify/singular_point.hpp, verify/exact_point.hpp): proved only
// where exact arithmetic finds the rank drop, and named by their second-order form, checked
// against systems whose singular points are known in closed form.
#include "verify/singular_point.hpp"

#include <catch2/catch.hpp>

using namespace linkbox;
using model::Polynomial;

namespace {

Polynomial v(int i) { return Polynomial::variable(i); }
Polynomial c(double x) { return Polynomial::constant(Interval(x)); }

// The parallelogram four-bar (crank = rocker = 1, coupler = ground = 3) over (c1, s1, c3,
// s3); `coupler_sq` 9 + d moves the coupler's length off the parallelogram's.
std::vector<Polynomial> parallelogram(double coupler_sq = 9) {
  const Polynomial dx = c(3) + v(2) - v(0), dy = v(3) - v(1);
  return {v(0) * v(0) + v(1) * v(1) - c(1), v(2) * v(2) + v(3) * v(3) - c(1), dx * dx + dy * dy - c(coupler_sq)};
}

Box around(std::vector<double> p, double r) {
  Box b;
  for (double x : p) b.push_back(Interval(x - r, x + r));
  return b;
}

}  // namespace

TEST_CASE("the simplest rational in an interval is found exactly", "[verify][singular]") {
  CHECK(verify::simplest_rational(0.9999999999999998, 1.0000000000000002) == "1");
  CHECK(verify::simplest_rational(-1e-17, 2e-17) == "0");
  CHECK(verify::simplest_rational(0.33333333333333331, 0.33333333333333337) == "1/3");
  CHECK(verify::simplest_rational(-0.75, -0.74) == "-3/4");
  CHECK_FALSE(verify::simplest_rational(1, 0));
  CHECK(verify::rational_in("1/3", Interval(0.333, 0.334)));
  CHECK_FALSE(verify::rational_in("1/3", Interval(0.3334, 0.34)));
  CHECK_FALSE(verify::rational_in("x/3", Interval(0, 1)));
}

TEST_CASE("exact arithmetic names the rank drop and the second-order form", "[verify][singular]") {
  // The change point (1, 0, 1, 0): two branches cross there.
  CHECK(verify::exact_singular_kind(parallelogram(), {"1", "0", "1", "0"}) == verify::SingularKind::crossing);
  // A regular point of the curve ((3/5, 4/5) for both cranks) and a point off it are not.
  CHECK_FALSE(verify::exact_singular_kind(parallelogram(), {"3/5", "4/5", "3/5", "4/5"}));
  CHECK_FALSE(verify::exact_singular_kind(parallelogram(), {"1", "0", "1", "1/1000000"}));
  // x^2 + y^2 = 0 (with z free, a plane's worth of unknowns) is one point: definite form.
  const std::vector<Polynomial> dot{v(0) * v(0) + v(1) * v(1), v(2)};
  CHECK(verify::exact_singular_kind(dot, {"0", "0", "0"}) == verify::SingularKind::isolated);
  // y^2 = x^3 (a cusp): the form is degenerate.
  const std::vector<Polynomial> cusp{v(1) * v(1) - v(0) * v(0) * v(0), v(2)};
  CHECK(verify::exact_singular_kind(cusp, {"0", "0", "0"}) == verify::SingularKind::degenerate);
}

TEST_CASE("a change point is proved the only singular point of its box", "[verify][singular]") {
  for (double sign : {-1.0, 1.0}) {
    const auto h = parallelogram();
    auto s = verify::prove_singular_point(h, 0, around({sign, 0.004, sign, -0.003}, 0.01), 0.05, {});
    REQUIRE(s);
    CHECK(s->point == std::vector<std::string>{sign > 0 ? "1" : "-1", "0", sign > 0 ? "1" : "-1", "0"});
    CHECK(s->kind == verify::SingularKind::crossing);
    const Box u = s->where();
    REQUIRE(u.size() == 4);
    CHECK(contains(u[1], 0.0));
    CHECK(max_width(u) > 1e-4);  // wide enough for arcs to reach it
    // The checker's path accepts it; a moved point, a wrong l or a widened box is refused.
    CHECK(verify::reprove_singular_point(h, *s));
    auto moved = *s;
    moved.point[1] = "1/1000000000000";
    CHECK_FALSE(verify::reprove_singular_point(h, moved));
    auto tilted = *s;
    tilted.normal[0] += 0.5;
    CHECK_FALSE(verify::reprove_singular_point(h, tilted));
    auto wide = *s;
    for (auto& x : wide.box) x = Interval(x.lower() - 1, x.upper() + 1);
    CHECK_FALSE(verify::reprove_singular_point(h, wide));
  }
}

TEST_CASE("an avoided crossing has no proved singular point", "[verify][singular]") {
  // Coupler length moved by about 1e-9: the two modes no longer meet (no exact zero there).
  for (double d : {1e-9, -1e-9}) {
    const auto h = parallelogram(9 + d);
    CHECK_FALSE(verify::prove_singular_point(h, 0, around({1, 0, 1, 0}, 0.01), 0.05, {}));
  }
}
