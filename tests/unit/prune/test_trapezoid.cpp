// Trapezoid clipping must never remove a zero of a multi-affine function: random functions
// with planted roots, including roots on box faces and corners.
#include "prune/trapezoid.hpp"

#include <catch2/catch.hpp>

#include <random>

using namespace linkbox;
using model::Polynomial;

namespace {

// Random multi-affine polynomial in `vars` vanishing at `root` (value at root subtracted
// exactly in interval arithmetic: the constant term is an interval that contains the
// value making the root exact).
Polynomial planted(std::mt19937& rng, const std::vector<int>& vars, const std::vector<double>& root) {
  std::uniform_real_distribution<double> coef(-2, 2);
  std::bernoulli_distribution keep(0.7);
  Polynomial p;
  for (size_t mask = 1; mask < (size_t{1} << vars.size()); ++mask) {
    if (!keep(rng)) continue;
    Polynomial m = Polynomial::constant(Interval(coef(rng)));
    for (size_t j = 0; j < vars.size(); ++j)
      if (mask >> j & 1) m = m * Polynomial::variable(vars[j]);
    p += m;
  }
  Box at;
  for (double r : root) at.push_back(Interval(r));
  return p - Polynomial::constant(p.eval(at));
}

}  // namespace

TEST_CASE("clip_to_trapezoid keeps the zero of a line and rounds outward", "[trapezoid]") {
  RoundingGuard guard;
  // f goes from 1 at x=0 to -2 at x=3: zero at x=1.
  double lo = 0, hi = 3;
  REQUIRE(prune::clip_to_trapezoid(lo, hi, 1, 1, -2, -2));
  CHECK(lo <= 1.0);
  CHECK(lo > 0.999999);
  // A line is its own trapezoid: both edges clip, to the zero itself.
  CHECK(hi >= 1.0);
  CHECK(hi < 1.000001);
  // Zero at 1/3 (not a double): the clipped box must still contain it.
  lo = 0, hi = 1;
  REQUIRE(prune::clip_to_trapezoid(lo, hi, 1, 1, -2, -2));  // 1 - 3x = 0
  CHECK(static_cast<long double>(lo) * 3 <= 1.0L);
  CHECK(static_cast<long double>(hi) * 3 >= 1.0L);
  CHECK(hi - lo < 1e-15);
  // Both ends positive: empty.
  lo = 0, hi = 1;
  CHECK_FALSE(prune::clip_to_trapezoid(lo, hi, 0.5, 1, 0.1, 2));
  // Touching zero exactly at the right end stays feasible.
  lo = 0, hi = 1;
  REQUIRE(prune::clip_to_trapezoid(lo, hi, 1, 1, 0, 0));
  CHECK(hi == 1);
}

TEST_CASE("trapezoid clipping never removes a planted root", "[trapezoid]") {
  std::mt19937 rng(12345);
  std::uniform_int_distribution<int> nvars(1, 5), neqs(1, 4);
  std::uniform_real_distribution<double> u(-1, 1), w(1e-9, 2);
  int placed_on_face = 0, emptied_wrongly = 0, cases = 3000;
  for (int c = 0; c < cases; ++c) {
    const int n = nvars(rng);
    Box box(n);
    std::vector<double> root(n);
    for (int i = 0; i < n; ++i) {
      double lo = u(rng), width = w(rng);
      box[i] = Interval(lo, lo + width);
      // A third of the coordinates on a face (either end), the rest inside.
      switch (rng() % 6) {
        case 0: root[i] = box[i].lower(); ++placed_on_face; break;
        case 1: root[i] = box[i].upper(); ++placed_on_face; break;
        default: root[i] = lo + width * std::uniform_real_distribution<double>(0, 1)(rng);
      }
      if (root[i] > box[i].upper()) root[i] = box[i].upper();
    }
    std::vector<Polynomial> eqs;
    const int m = neqs(rng);
    for (int e = 0; e < m; ++e) {
      std::vector<int> vars;
      for (int i = 0; i < n; ++i)
        if (rng() % 3 || vars.empty()) vars.push_back(i);
      eqs.push_back(planted(rng, vars, root));
    }
    prune::Trapezoid t(eqs);
    Box b = box;
    for (int pass = 0; pass < 5; ++pass) {
      if (t.contract(b) == prune::Outcome::empty) {
        ++emptied_wrongly;
        break;
      }
      for (int i = 0; i < n; ++i) REQUIRE(contains(b[i], root[i]));
    }
  }
  CHECK(emptied_wrongly == 0);
  CHECK(placed_on_face > 1000);
}

TEST_CASE("trapezoid clipping empties a box without roots and shrinks towards a root", "[trapezoid]") {
  // x + y - 3 = 0 has no root in [0,1]^2.
  Polynomial f = Polynomial::variable(0) + Polynomial::variable(1) - Polynomial::constant(Interval(3.0));
  prune::Trapezoid t({f});
  Box b{Interval(0, 1), Interval(0, 1)};
  CHECK(t.contract(b) == prune::Outcome::empty);
  // x*y - 0.25 = 0, x - y = 0 in [0,1]^2: root (0.5, 0.5); the box shrinks.
  Polynomial g = Polynomial::variable(0) * Polynomial::variable(1) - Polynomial::constant(Interval(0.25));
  Polynomial h = Polynomial::variable(0) - Polynomial::variable(1);
  prune::Trapezoid t2({g, h});
  Box c{Interval(0, 1), Interval(0, 1)};
  for (int i = 0; i < 50 && t2.contract(c) == prune::Outcome::shrunk;) ++i;
  CHECK(contains(c[0], 0.5));
  // One equation at a time: x*y >= 0.25 alone clips x, y to [0.25, 1] and x - y adds
  // nothing (the cluster problem the paper mentions); splitting does the rest.
  CHECK(c[0].lower() >= 0.2499999);
  CHECK(c[1].lower() >= 0.2499999);
}

TEST_CASE("trapezoid refuses equations that are not multi-affine", "[trapezoid]") {
  Polynomial sq = Polynomial::variable(0) * Polynomial::variable(0);
  CHECK_THROWS_AS(prune::Trapezoid({sq}), std::invalid_argument);
}
