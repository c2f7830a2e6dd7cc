// Exact roots (verify/exact_point.hpp): a rational point is taken as the root only where every
// equation is exactly 0, and its side of an angle's domain is decided by its angle, checked
// on points whose angles are known in closed form against domain ends a rounding away.
#include "interval/rigorous.hpp"
#include "verify/exact_point.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace linkbox;
using model::Polynomial;

namespace {

Polynomial v(int i) { return Polynomial::variable(i); }
Polynomial c(double x) { return Polynomial::constant(Interval(x)); }

// The angle t in [lo, hi] on the unit circle (c, s) = (x0, x1), as the lifting writes it.
model::Inequality arc(double lo, double hi) {
  const Interval m = (Interval(lo) + Interval(hi)) / Interval(2.0), h = (Interval(hi) - Interval(lo)) / Interval(2.0);
  model::Inequality q;
  q.g = Polynomial::constant(rigorous::cos(h)) - v(0) * rigorous::cos(m) - v(1) * rigorous::sin(m);
  q.name = "domain of t";
  q.arc = model::Inequality::Arc{0, 1, rigorous::cos(m), rigorous::sin(m), h, Interval(lo, hi)};
  return q;
}

model::Side side(double lo, double hi, std::vector<std::string> point) { return verify::exact_side(arc(lo, hi), point); }

}  // namespace

TEST_CASE("an exact root is found only where every equation vanishes exactly", "[verify][exact]") {
  // sin t = 0 on the circle: (1, 0) is a root; near (3/5, 4/5) nothing vanishes.
  const std::vector<Polynomial> f = {v(1), v(0) * v(0) + v(1) * v(1) - c(1)};
  const Box at_one = {Interval(1 - 1e-15, 1 + 1e-15), Interval(-1e-15, 1e-15)};
  const auto p = verify::exact_zero_in(f, at_one);
  REQUIRE(p);
  CHECK(*p == std::vector<std::string>{"1", "0"});
  CHECK(verify::exact_zero(f, {"1", "0"}));
  CHECK_FALSE(verify::exact_zero(f, {"3/5", "4/5"}));
  CHECK_FALSE(verify::exact_zero_in(f, {Interval(0.6 - 1e-15, 0.6 + 1e-15), Interval(0.8 - 1e-15, 0.8 + 1e-15)}));
  // A coefficient that is not a point (a rounded constant) never gives an exact root.
  const std::vector<Polynomial> rounded = {v(1) - Polynomial::constant(Interval(-1e-300, 1e-300)), f[1]};
  CHECK_FALSE(verify::exact_zero_in(rounded, at_one));
  CHECK(verify::rationals_in({"1", "0"}, {Interval(0, 1), Interval(0, 0)}));
  CHECK_FALSE(verify::rationals_in({"1", "0"}, {Interval(0, 0.9999999999999999), Interval(0, 0)}));
}

TEST_CASE("an exact point's angle decides its domain's arc, also at the arc's ends", "[verify][exact]") {
  const double two_pi_below = 6.283185307179586, two_pi_above = std::nextafter(two_pi_below, 7.0);
  const double half_pi_below = 1.5707963267948966, half_pi_above = std::nextafter(half_pi_below, 2.0);
  REQUIRE(two_pi_below < 2 * M_PI + 1e-15);
  // (1, 0): the angle 0, or 2 pi; 0 is a double and compared exactly.
  CHECK(side(0, 3, {"1", "0"}) == model::Side::inside);
  CHECK(side(-3, 0, {"1", "0"}) == model::Side::inside);
  CHECK(side(std::ldexp(1.0, -60), 3, {"1", "0"}) == model::Side::outside);
  CHECK(side(0.1, two_pi_above, {"1", "0"}) == model::Side::inside);
  CHECK(side(0.1, two_pi_below, {"1", "0"}) == model::Side::outside);
  // (0, 1): pi / 2, between two doubles.
  CHECK(side(0, half_pi_above, {"0", "1"}) == model::Side::inside);
  CHECK(side(0, half_pi_below, {"0", "1"}) == model::Side::outside);
  CHECK(side(half_pi_below, 3, {"0", "1"}) == model::Side::inside);
  CHECK(side(half_pi_above, 3, {"0", "1"}) == model::Side::outside);
  // (3/5, 4/5): atan(4/3) = 0.927295218001612232428512462922...
  const double a = 0.9272952180016122;
  CHECK(side(a - 1e-15, 1, {"3/5", "4/5"}) == model::Side::inside);
  CHECK(side(std::nextafter(a, 1.0) + 1e-16, 1, {"3/5", "4/5"}) == model::Side::outside);
  // Off the circle: no angle, nothing decided.
  CHECK(side(0, 3, {"1/2", "0"}) == model::Side::boundary);
}

TEST_CASE("an exact point decides a polynomial inequality by its exact sign", "[verify][exact]") {
  model::Inequality q;
  q.g = v(0) + v(1) - c(1);  // x + y <= 1
  CHECK(verify::exact_side(q, {"1/3", "2/3"}) == model::Side::inside);
  CHECK(verify::exact_side(q, {"1/3", "3/4"}) == model::Side::outside);
  q.strict = true;  // x + y < 1
  CHECK(verify::exact_side(q, {"1/3", "2/3"}) == model::Side::outside);
  q.g = v(0) - Polynomial::constant(rigorous::pi());  // a rounded coefficient: undecided
  CHECK(verify::exact_side(q, {"1", "0"}) == model::Side::boundary);
}
