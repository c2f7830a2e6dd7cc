// Root certification: known simple roots certify in boxes near the rounding limit, double
// roots and root-free boxes never certify, and certificates re-check from (F, box, C) alone.
#include "interval/rigorous.hpp"
#include "newton/certify.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using linkbox::Box;
using linkbox::Interval;
using linkbox::model::Polynomial;
using namespace linkbox::newton;

namespace {

Polynomial var(int i) { return Polynomial::variable(i); }
Polynomial cst(const Interval& c) { return Polynomial::constant(c); }
Polynomial cst(double c) { return cst(Interval(c)); }

Box widened(const Box& b, double r) {
  Box w;
  for (auto& x : b) w.push_back(x + Interval(-r, r));
  return w;
}

bool certified(const Certificate& c) { return c.status == Status::certified; }

bool strictly_inside(const Box& inner, const Box& outer) {
  for (size_t i = 0; i < inner.size(); ++i)
    if (!(outer[i].lower() < inner[i].lower() && inner[i].upper() < outer[i].upper())) return false;
  return true;
}

// x^2 + y^2 = 1 and x = y.
const std::vector<Polynomial> kCircleLine{var(0) * var(0) + var(1) * var(1) - cst(1), var(0) - var(1)};

}  // namespace

TEST_CASE("interval Eigen: products enclose and stay unambiguous", "[newton][eigen]") {
  IMatrix a(2, 2);
  a << Interval(1), Interval(2), Interval(3), Interval(1, 2);
  IVector x(2);
  x << Interval(1) / Interval(3), Interval(-1, 1);
  IVector ax = a * x;  // interval * interval through Eigen itself
  IMatrix twice = 2.0 * a;
  CHECK(linkbox::contains(ax(0), 1.0 / 3 + 2));
  CHECK(linkbox::contains(ax(1), 1.0 - 2));
  CHECK(twice(1, 1).lower() == 2);
  Eigen::MatrixXd c(2, 2);
  c << 0.1, 0.2, 0.3, 0.4;
  IVector cx = multiply(c, x);
  CHECK(cx(0).lower() <= 0.1 / 3 - 0.2);
  CHECK(cx(0).upper() >= 0.1 / 3 + 0.2);
  IMatrix m = identity_minus(c, to_interval(Eigen::MatrixXd::Identity(2, 2)));
  CHECK(linkbox::contains(m(0, 0), 0.9));
  CHECK(norm_inf_upper(m) >= 1.0999);
}

TEST_CASE("certify_root: circle meets line at (1/sqrt2, 1/sqrt2)", "[newton]") {
  auto method = GENERATE(Method::krawczyk, Method::hansen_sengupta);
  NewtonOptions o;
  o.method = method;
  Box hull{{0.6, 0.8}, {0.6, 0.8}};
  Certificate c = certify_root(kCircleLine, hull, {}, o);
  REQUIRE(certified(c));
  CHECK(c.reason == Reason::none);
  Interval root = linkbox::rigorous::sqrt(Interval(0.5));  // tight enclosure of 1/sqrt(2)
  for (int i = 0; i < 2; ++i) {
    CHECK(c.box[i].lower() <= root.lower());
    CHECK(c.box[i].upper() >= root.upper());
    CHECK(linkbox::overlaps(Box{c.image[i]}, Box{root}));
  }
  CHECK(linkbox::max_width(c.box) < 1e-10);
  CHECK(linkbox::max_width(c.box) < 1e-13);  // well conditioned: a few ulps
  CHECK(strictly_inside(c.image, c.box));
  CHECK(c.unique_in_hull);
  CHECK(c.root_in_domain);
  CHECK(recheck(kCircleLine, c));

  // A hull holding both roots certifies one of them, without claiming it is alone.
  Certificate wide = certify_root(kCircleLine, {{-2, 2}, {-2, 2}}, {}, o);
  REQUIRE(certified(wide));
  CHECK_FALSE(wide.unique_in_hull);
  CHECK(linkbox::max_width(wide.box) < 1e-10);
}

TEST_CASE("certify_root: 3x3 system with eight planted roots", "[newton]") {
  // (x - 1/3)(x + 1/2) = 0, (y - 2x)(y + 3/2) = 0, (z - xy)(z - 2) = 0: eight simple roots,
  // one coefficient only known as an interval.
  const Interval third = Interval(1) / Interval(3);
  std::vector<Polynomial> f{(var(0) - cst(third)) * (var(0) + cst(0.5)),
                            (var(1) - cst(2) * var(0)) * (var(1) + cst(1.5)),
                            (var(2) - var(0) * var(1)) * (var(2) - cst(2))};
  auto method = GENERATE(Method::krawczyk, Method::hansen_sengupta);
  NewtonOptions o;
  o.method = method;
  int count = 0;
  for (Interval x : {third, Interval(-0.5)})
    for (Interval y : {Interval(2) * x, Interval(-1.5)})
      for (Interval z : {x * y, Interval(2)}) {
        Box root{x, y, z};
        Certificate c = certify_root(f, widened(root, 0.01), {}, o);
        INFO("root " << linkbox::to_string(root));
        REQUIRE(certified(c));
        CHECK(linkbox::overlaps(c.image, root));
        CHECK(linkbox::max_width(c.box) < 1e-10);
        CHECK(c.unique_in_hull);
        CHECK(recheck(f, c));
        ++count;
      }
  CHECK(count == 8);

  Certificate all = certify_root(f, {{-1, 1}, {-2, 2}, {-1, 3}}, {}, o);
  CHECK(certified(all));
  CHECK_FALSE(all.unique_in_hull);

  // The root (-1/2, -3/2, 2) exactly at a corner of the hull.
  Certificate corner = certify_root(f, {{-0.5, -0.4}, {-1.6, -1.5}, {2, 2.1}}, {}, o);
  REQUIRE(certified(corner));
  CHECK(linkbox::contains(corner.box, Box{Interval(-0.5), Interval(-1.5), Interval(2)}));
  CHECK(linkbox::max_width(corner.box) < 1e-10);
}

TEST_CASE("certify_root: root exactly on a face of the hull or the domain", "[newton]") {
  std::vector<Polynomial> f{var(0) * var(0) + var(1) * var(1) - cst(1), var(1)};  // root (1, 0)
  Box hull{{0.9, 1.0}, {-0.1, 0.1}}, root{Interval(1), Interval(0)};

  Certificate inside = certify_root(f, hull, {{-2, 2}, {-2, 2}});
  REQUIRE(certified(inside));
  CHECK(linkbox::contains(inside.box, root));
  CHECK(linkbox::max_width(inside.box) < 1e-10);
  CHECK_FALSE(inside.on_domain_boundary);
  CHECK(inside.root_in_domain);

  // The hull is also the domain: the certificate box straddles the face x = 1.
  Certificate boundary = certify_root(f, hull, hull);
  REQUIRE(certified(boundary));
  CHECK(boundary.on_domain_boundary);
  CHECK(linkbox::contains(boundary.box, root));
  CHECK(recheck(f, boundary));

  NewtonOptions strict;
  strict.domain_slack = 0;
  Certificate refused = certify_root(f, hull, hull, strict);
  CHECK_FALSE(certified(refused));
  CHECK(refused.reason == Reason::outside_domain);

  // The domain ends a few ulps past the root: the certificate box is cut back into it.
  Certificate cut = certify_root(f, hull, {{-2, 1 + 1e-15}, {-1, 1}});
  REQUIRE(certified(cut));
  CHECK_FALSE(cut.on_domain_boundary);
  CHECK(cut.box[0].upper() <= 1 + 1e-15);
  CHECK(linkbox::contains(cut.box, root));

  // A domain the root is clearly outside of.
  Certificate outside = certify_root(f, hull, {{0, 0.99}, {-1, 1}});
  CHECK_FALSE(certified(outside));
  CHECK(outside.reason == Reason::outside_domain);
}

TEST_CASE("certify_root: double roots are never certified", "[newton]") {
  auto method = GENERATE(Method::krawczyk, Method::hansen_sengupta);
  NewtonOptions o;
  o.method = method;
  auto singular_reason = [](const Certificate& c) {
    return c.reason == Reason::singular_jacobian || c.reason == Reason::inflation_failed ||
           c.reason == Reason::singular_in_box;
  };
  std::vector<Polynomial> square{var(0) * var(0)};
  for (Box hull : {Box{{-0.3, 0.5}}, Box{{-1, 1}}, Box{{-1e-8, 2e-8}}, Box{{0, 0.25}}}) {
    Certificate c = certify_root(square, hull, {}, o);
    INFO(linkbox::to_string(hull) << ": " << to_string(c.reason));
    CHECK_FALSE(certified(c));
    CHECK(singular_reason(c));
  }
  // The unit circle touching the line y = 1 at (0, 1).
  std::vector<Polynomial> tangent{var(0) * var(0) + var(1) * var(1) - cst(1), var(1) - cst(1)};
  for (Box hull : {Box{{-0.2, 0.3}, {0.9, 1.1}}, Box{{-0.1, 0.1}, {0.95, 1.05}}, Box{{-1e-9, 3e-9}, {1, 1.5}}}) {
    Certificate c = certify_root(tangent, hull, {}, o);
    INFO(linkbox::to_string(hull) << ": " << to_string(c.reason));
    CHECK_FALSE(certified(c));
    CHECK(singular_reason(c));
  }
}

TEST_CASE("certify_root: boxes without a root are not certified", "[newton]") {
  auto method = GENERATE(Method::krawczyk, Method::hansen_sengupta);
  NewtonOptions o;
  o.method = method;
  Certificate far = certify_root(kCircleLine, {{2, 3}, {2, 3}}, {}, o);
  CHECK_FALSE(certified(far));
  CHECK(far.reason == Reason::no_root);
  // Just short of the root (0.7071 < 1/sqrt(2)): Newton finds it outside the hull.
  Certificate near = certify_root(kCircleLine, {{0.70, 0.7071}, {0.70, 0.7071}}, {}, o);
  CHECK_FALSE(certified(near));
  CHECK((near.reason == Reason::outside_hull || near.reason == Reason::no_root));
}

TEST_CASE("certify_root: a box between a close pair of roots is proved empty where no inverse is usable", "[newton]") {
  auto method = GENERATE(Method::krawczyk, Method::hansen_sengupta);
  NewtonOptions o;
  o.method = method;
  // x^2 = 1e-6 and y = 0: roots (+-1e-3, 0), and the Jacobian diag(2x, 1) is singular on x = 0.
  const std::vector<Polynomial> pair{var(0) * var(0) - cst(1e-6), var(1)};
  const Box between{{-1e-4, 1e-4}, {-1e-4, 1e-4}};
  Certificate c = certify_root(pair, between, {}, o);
  CHECK(c.reason == Reason::no_root);
  CHECK(recheck_exclusion(pair, c.box, c.preconditioner, c.method));
  // Boxes that hold a root, a simple one of the pair or the circle's tangent point: never empty.
  std::vector<Polynomial> tangent{var(0) * var(0) + var(1) * var(1) - cst(1), var(1) - cst(1)};
  for (const auto& [f, hull] : {std::pair{pair, Box{{-1e-4, 2e-3}, {-1e-4, 1e-4}}},
                                std::pair{pair, Box{{-2e-3, 1e-4}, {-1e-4, 1e-4}}},
                                std::pair{tangent, Box{{-1e-4, 1e-4}, {1 - 1e-4, 1 + 1e-4}}},
                                std::pair{tangent, Box{{-1e-4, 2e-4}, {1, 1 + 1e-4}}}}) {
    INFO(linkbox::to_string(hull));
    CHECK(certify_root(f, hull, {}, o).reason != Reason::no_root);
  }
}

TEST_CASE("certify_root: malformed input", "[newton]") {
  CHECK(certify_root(kCircleLine, {{0, 1}, {0, 1}, {0, 1}}).reason == Reason::not_square);
  CHECK(certify_root(kCircleLine, {{0, 1}}).reason == Reason::not_square);
  CHECK(certify_root(kCircleLine, {{0, 1}, {0, 1}}, {{0, 1}}).reason == Reason::not_square);
  CHECK(certify_root(kCircleLine, {{0, linkbox::kInf}, {0, 1}}).reason == Reason::non_finite);
}

TEST_CASE("recheck_krawczyk: needs the exact box and a sensible C", "[newton]") {
  Box hull{{0.6, 0.8}, {0.6, 0.8}};
  Certificate c = certify_root(kCircleLine, hull);
  REQUIRE(certified(c));
  CHECK(recheck_krawczyk(kCircleLine, c.box, c.preconditioner));

  // Shifted off the root by a few of its own widths.
  Box shifted = c.box;
  for (auto& x : shifted) x = x + Interval(3 * linkbox::width_up(x));
  CHECK_FALSE(recheck_krawczyk(kCircleLine, shifted, c.preconditioner));
  // Heavily perturbed preconditioners.
  CHECK_FALSE(recheck_krawczyk(kCircleLine, c.box, 3.0 * c.preconditioner));
  CHECK_FALSE(recheck_krawczyk(kCircleLine, c.box, -c.preconditioner));
  CHECK_FALSE(recheck_krawczyk(kCircleLine, c.box, Eigen::MatrixXd::Zero(2, 2)));
  Eigen::MatrixXd swapped = c.preconditioner.rowwise().reverse();
  CHECK_FALSE(recheck_krawczyk(kCircleLine, c.box, swapped));
  // Wrong shapes are refused, not trusted.
  CHECK_FALSE(recheck_krawczyk(kCircleLine, c.box, Eigen::MatrixXd::Identity(3, 3)));
  CHECK_FALSE(recheck_krawczyk(kCircleLine, {c.box[0]}, c.preconditioner));

  NewtonOptions hs;
  hs.method = Method::hansen_sengupta;
  Certificate h = certify_root(kCircleLine, hull, {}, hs);
  REQUIRE(certified(h));
  CHECK(recheck_hansen_sengupta(kCircleLine, h.box, h.preconditioner));
  CHECK_FALSE(recheck_hansen_sengupta(kCircleLine, shifted, h.preconditioner));
}

TEST_CASE("certify_curve_crossing on the unit circle", "[newton][curve]") {
  std::vector<Polynomial> circle{var(0) * var(0) + var(1) * var(1) - cst(1)};
  Box box{{0.5, 0.9}, {0.3, 0.9}};

  Certificate at_x = certify_curve_crossing(circle, box, 0);
  REQUIRE(certified(at_x));
  CHECK(at_x.fixed_variable == 0);
  CHECK(at_x.box[0].lower() == 0.7);
  CHECK(at_x.box[0].upper() == 0.7);
  Interval y = linkbox::rigorous::sqrt(Interval(1) - Interval(0.7) * Interval(0.7));
  CHECK(linkbox::overlaps(Box{at_x.image[1]}, Box{y}));
  CHECK(linkbox::max_width(at_x.box) < 1e-10);
  CHECK(recheck_curve_crossing(circle, at_x.box, 0, at_x.preconditioner));
  CHECK(recheck(circle, at_x));
  CHECK_FALSE(recheck_curve_crossing(circle, box, 0, at_x.preconditioner));  // side not fixed

  Certificate at_y = certify_curve_crossing(circle, box, 1);
  REQUIRE(certified(at_y));
  CHECK(linkbox::overlaps(Box{at_y.image[0]}, Box{linkbox::rigorous::sqrt(Interval(1) - Interval(0.6) * Interval(0.6))}));

  // Where the circle is vertical (x = 1), fixing x meets it tangentially; y works.
  Box vertical{{0.9, 1.1}, {-0.1, 0.1}};
  CHECK_FALSE(certified(certify_curve_crossing(circle, vertical, 0)));
  Certificate chosen = certify_curve_crossing(circle, vertical);
  REQUIRE(certified(chosen));
  CHECK(chosen.fixed_variable == 1);
  CHECK(recheck(circle, chosen));

  CHECK_FALSE(certified(certify_curve_crossing(circle, {{2, 3}, {2, 3}})));
  CHECK(certify_curve_crossing(kCircleLine, box).reason == Reason::not_square);

  // A space curve: the unit sphere cut by the plane x = z, near (1/2, 1/sqrt2, 1/2).
  std::vector<Polynomial> space{var(0) * var(0) + var(1) * var(1) + var(2) * var(2) - cst(1), var(0) - var(2)};
  Certificate s = certify_curve_crossing(space, {{0.4, 0.6}, {0.6, 0.8}, {0.4, 0.6}});
  REQUIRE(certified(s));
  CHECK(recheck(space, s));
}

TEST_CASE("certify_root: a root with a coordinate exactly 0, from a hull at the rounding limit", "[newton]") {
  // x1^2 + x2 - 1/4 = 0, x1 - x2^2 + 1/16 = 0: root (0, 1/4), regular (det J = -1). Search
  // contraction leaves x1 in [-1.4e-17, 0]; inflation around a zero coordinate must still
  // reach a width the Newton image fits in (tests/data/planted/zero-coordinate-inflation.toml).
  auto method = GENERATE(Method::krawczyk, Method::hansen_sengupta);
  NewtonOptions o;
  o.method = method;
  const std::vector<Polynomial> f{var(0) * var(0) + var(1) - cst(0.25), var(0) - var(1) * var(1) + cst(0.0625)};
  for (const Box& hull : {Box{Interval(-1.4e-17, 0), Interval(0.25)}, Box{Interval(0), Interval(0.25)},
                          Box{Interval(-1e-300, 1e-300), Interval(0.25, 0.25)}}) {
    const Certificate c = certify_root(f, hull, Box{Interval(-1, 1), Interval(-1, 1)}, o);
    INFO(to_string(c.reason));
    REQUIRE(certified(c));
    CHECK(linkbox::contains(c.box[0], 0.0));
    CHECK(linkbox::contains(c.box[1], 0.25));
    CHECK(c.box[0].upper() - c.box[0].lower() < 1e-10);
  }
}

TEST_CASE("interval Eigen: an interval matrix times an interval vector encloses every product", "[newton][eigen]") {
  IMatrix a(2, 2);
  a << Interval(1, 2), Interval(-1), Interval(0.1), Interval(-3, -2);
  IVector x(2);
  x << Interval(-1, 1), Interval(1) / Interval(3);
  const IVector ax = multiply(a, x);
  for (double a00 : {1.0, 2.0})
    for (double x0 : {-1.0, 1.0}) CHECK(linkbox::contains(ax(0), a00 * x0 - 1.0 / 3));
  for (double a11 : {-3.0, -2.0}) CHECK(linkbox::contains(ax(1), 0.1 * -1 + a11 / 3));
  CHECK(ax(1).lower() <= -0.1 - 1.0);
}

TEST_CASE("interval Eigen: products over a sparse B equal the entry-wise sums", "[newton][eigen]") {
  // The products skip B's exact zeros; each entry must still be the outward-rounded sum over
  // every k, here recomputed one term at a time in protected Interval arithmetic.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = 9;
  Eigen::MatrixXd a(n, n);
  IMatrix b(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      a(i, j) = u(rng) / 3;
      const double c = u(rng);
      b(i, j) = (i + 2 * j) % 3 == 0 ? Interval(c, c + 1e-3) : Interval(0.0);
    }
  const IMatrix ab = multiply(a, b), r = identity_minus(a, b);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      Interval s(0.0), t(i == j ? 1.0 : 0.0);
      for (int k = 0; k < n; ++k) s += Interval(a(i, k)) * b(k, j), t -= Interval(a(i, k)) * b(k, j);
      CHECK(ab(i, j).lower() == s.lower());
      CHECK(ab(i, j).upper() == s.upper());
      CHECK(r(i, j).lower() == t.lower());
      CHECK(r(i, j).upper() == t.upper());
    }
  // A non-finite preconditioner entry times an exact zero is not skipped: no finite entry
  // is made up where the dense product has none.
  a(0, 1) = linkbox::kInf;
  const IMatrix bad = identity_minus(a, b);
  for (int j = 0; j < n; ++j) CHECK_FALSE((std::isfinite(bad(0, j).lower()) && std::isfinite(bad(0, j).upper())));
}
