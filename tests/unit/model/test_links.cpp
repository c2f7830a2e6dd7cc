// Links y = f(a) (model/link.hpp): the enclosures hold the function's values, narrowing never
// removes a point of the link, the domain is respected, and the compiled rows are y - f(a)
// with the Jacobian entries 1 and -f'(a).
#include "interval/rigorous.hpp"
#include "model/compiled.hpp"
#include "model/link.hpp"
#include "prune/links.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace linkbox;
using model::Elementary;
using model::Link;

namespace {

struct Case {
  Elementary f;
  double lo, hi;  // where arguments are drawn (inside the domain)
  long double (*exact)(long double);
};

long double f_exp(long double x) { return expl(x); }
long double f_log(long double x) { return logl(x); }
long double f_sinh(long double x) { return sinhl(x); }
long double f_cosh(long double x) { return coshl(x); }
long double f_tanh(long double x) { return tanhl(x); }
long double f_asinh(long double x) { return asinhl(x); }
long double f_acosh(long double x) { return acoshl(x); }
long double f_atanh(long double x) { return atanhl(x); }
long double f_asin(long double x) { return asinl(x); }
long double f_acos(long double x) { return acosl(x); }
long double f_atan(long double x) { return atanl(x); }
long double f_sin(long double x) { return sinl(x); }
long double f_cos(long double x) { return cosl(x); }
long double f_tan(long double x) { return tanl(x); }

const Case kCases[] = {
    {Elementary::exp, -20, 20, f_exp}, {Elementary::log, 1e-3, 50, f_log},
    {Elementary::sinh, -8, 8, f_sinh},        {Elementary::cosh, -8, 8, f_cosh},
    {Elementary::tanh, -5, 5, f_tanh},        {Elementary::asin, -0.999, 0.999, f_asin},
    {Elementary::acos, -0.999, 0.999, f_acos}, {Elementary::atan, -30, 30, f_atan},
    {Elementary::sin, -7, 7, f_sin},          {Elementary::cos, -7, 7, f_cos},
    {Elementary::asinh, -50, 50, f_asinh},    {Elementary::acosh, 1.001, 50, f_acosh},
    {Elementary::atanh, -0.999, 0.999, f_atanh}, {Elementary::tan, -4, 4, f_tan},  // three branches
};

// The long double value, widened by a few of its ulps: an independent (libm) enclosure.
Interval reference(const Case& c, double a) {
  const long double v = c.exact(a);
  const long double slack = 8 * std::fabs(v) * 1.0842021724855044e-19L + 1e-300L;
  return Interval(static_cast<double>(std::nextafter(static_cast<double>(v - slack), -kInf)),
                  static_cast<double>(std::nextafter(static_cast<double>(v + slack), kInf)));
}

}  // namespace

TEST_CASE("link enclosures hold the function and its derivative", "[links]") {
  std::mt19937_64 rng(7);
  for (const Case& c : kCases) {
    INFO(model::to_string(c.f));
    std::uniform_real_distribution<double> pick(c.lo, c.hi);
    for (int i = 0; i < 200; ++i) {
      const double a = pick(rng);
      const Interval y = model::image(c.f, Interval(a));
      CHECK(overlap(y, reference(c, a)));
      CHECK(width(y) <= 1e-12 * (1 + std::fabs(median(y))));
      // The derivative over a small box holds the difference quotient's limit at a.
      const double h = 1e-6 * (1 + std::fabs(a));
      const Interval d = model::derivative(c.f, Interval(a - h, a + h));
      const double quotient = static_cast<double>((c.exact(a + h / 4) - c.exact(a - h / 4)) / (h / 2));
      const double tol = 1e-10 * (1 + std::fabs(quotient));  // the quotient's own rounding
      CHECK(overlap(d, Interval(quotient - tol, quotient + tol)));
    }
  }
}

TEST_CASE("a link's narrowing never removes a point of the link", "[links][soundness]") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const Case& c : kCases) {
    INFO(model::to_string(c.f));
    std::uniform_real_distribution<double> pick(c.lo, c.hi);
    const Link link{c.f, 1, 0, "f"};
    for (int i = 0; i < 500; ++i) {
      const double a = pick(rng);
      const Interval y = model::image(c.f, Interval(a));
      // A random box around (a, f(a)), its sides from tiny to wide (and beyond the domain).
      const double wa = std::pow(10.0, -8 + 9 * unit(rng)), wy = std::pow(10.0, -8 + 9 * unit(rng));
      Box box{Interval(a - wa * unit(rng), a + wa * unit(rng)), Interval(y.lower() - wy * unit(rng), y.upper() + wy * unit(rng))};
      REQUIRE(model::may_hold(link, box));
      REQUIRE(model::narrow(link, box));
      CHECK(contains(box[0], a));
      CHECK(subset(y, box[1]));
      prune::Links contractor({link});
      CHECK(contractor.contract(box) != prune::Outcome::empty);
      CHECK(contains(box[0], a));
      CHECK(subset(y, box[1]));
    }
  }
}

TEST_CASE("tan is enclosed on one branch and learns nothing across a pole", "[links]") {
  const Link tan{Elementary::tan, 1, 0, "tan"};
  CHECK(model::within_domain(Elementary::tan, Interval(1.5, 1.57)));
  CHECK_FALSE(model::within_domain(Elementary::tan, Interval(1.5, 1.6)));
  CHECK(!is_finite(model::image(Elementary::tan, Interval(1.5, 1.6))));
  CHECK(!is_finite(model::row_value(tan, Interval(0), Interval(1.5, 1.6))));
  // No slope bound across the pole (tan falls from +inf to -inf there): the whole line.
  CHECK(model::derivative(Elementary::tan, Interval(1.5, 1.6)).lower() == -kInf);
  // Across the pole, both tan(1.5) = 14.1 and tan(1.6) = -34.2 stay.
  Box box{Interval(1.5, 1.6), Interval(-40, 20)};
  REQUIRE(model::narrow(tan, box));
  CHECK(box[0].lower() == 1.5);
  CHECK(box[0].upper() == 1.6);
  // On the branch around pi, tan(a) in [-1, 1] leaves a in [3 pi / 4, 5 pi / 4].
  Box branch{Interval(2, 4), Interval(-1, 1)};
  REQUIRE(model::narrow(tan, branch));
  CHECK(std::fabs(branch[0].lower() - 3 * M_PI / 4) < 1e-12);
  CHECK(std::fabs(branch[0].upper() - 5 * M_PI / 4) < 1e-12);
}

TEST_CASE("a link holds only in its function's domain", "[links]") {
  const Link log{Elementary::log, 1, 0, "log"};
  Box box{Interval(-2, -0.5), Interval(-10, 10)};
  CHECK_FALSE(model::may_hold(log, box));
  CHECK_FALSE(model::narrow(log, box));
  box = {Interval(-1, 1), Interval(-100, 100)};
  REQUIRE(model::narrow(log, box));
  CHECK(box[0].lower() >= 0);
  CHECK(box[1].upper() >= 0);  // log(1) = 0 stays
  CHECK(box[1].lower() == -100);  // log reaches -inf near 0
  // Newton's row proves nothing across the domain's edge.
  CHECK(!is_finite(model::row_value(log, Interval(0), Interval(-1, 1))));
  CHECK(!is_finite(model::row_derivative(log, Interval(-1, 1))));
  const Link asin{Elementary::asin, 1, 0, "asin"};
  box = {Interval(0.5, 3), Interval(-10, 10)};
  REQUIRE(model::narrow(asin, box));
  CHECK(box[0].upper() == 1);
  CHECK(box[1].upper() <= 1.5708);
  CHECK(!is_finite(model::row_derivative(asin, Interval(0.5, 1))));  // asin' is unbounded at 1
  box = {Interval(2, 3), Interval(-10, 10)};
  CHECK_FALSE(model::narrow(asin, box));
  // exp > 0 and tanh in (-1, 1): a y box beyond them is empty.
  box = {Interval(-5, 5), Interval(-3, -1)};
  CHECK_FALSE(model::narrow({Elementary::exp, 1, 0, "exp"}, box));
  box = {Interval(-5, 5), Interval(1, 3)};
  CHECK_FALSE(model::narrow({Elementary::tanh, 1, 0, "tanh"}, box));
  // cosh: both branches are kept, the gap between them is not claimed.
  box = {Interval(-3, 3), Interval(2, 2)};
  REQUIRE(model::narrow({Elementary::cosh, 1, 0, "cosh"}, box));
  const double r = std::acosh(2.0);
  CHECK(contains(box[0], r));
  CHECK(contains(box[0], -r));
  CHECK(box[0].upper() < r + 1e-12);
  // acosh is defined from 1 and atanh strictly inside (-1, 1), where it tends to infinity.
  const Link acosh{Elementary::acosh, 1, 0, "acosh"};
  box = {Interval(-3, 0.9), Interval(-10, 10)};
  CHECK_FALSE(model::narrow(acosh, box));
  box = {Interval(0, 2), Interval(-10, 10)};
  REQUIRE(model::narrow(acosh, box));
  CHECK(box[0].lower() == 1);
  CHECK(box[1].lower() >= 0);
  CHECK(!is_finite(model::row_derivative(acosh, Interval(1, 2))));  // acosh' is unbounded at 1
  const Link atanh{Elementary::atanh, 1, 0, "atanh"};
  box = {Interval(1.5, 3), Interval(-10, 10)};
  CHECK_FALSE(model::narrow(atanh, box));
  box = {Interval(0.5, 3), Interval(0, 1)};
  REQUIRE(model::narrow(atanh, box));
  CHECK(box[0].upper() < std::tanh(1.0) + 1e-12);  // atanh(a) <= 1 keeps a below tanh(1)
  CHECK(!is_finite(model::row_value(atanh, Interval(0), Interval(0.5, 1))));
}

TEST_CASE("compiled links are the rows y - f(a) with entries 1 and -f'(a)", "[links]") {
  // x0 + x1 - 3 = 0 and x1 = exp(x0).
  const std::vector<model::Polynomial> eq{model::Polynomial::variable(0) + model::Polynomial::variable(1) -
                                          model::Polynomial::constant(Interval(3.0))};
  const model::CompiledSystem c(eq, {{Elementary::exp, 1, 0, "exp(x)"}}, 2);
  REQUIRE(c.rows() == 2);
  REQUIRE(c.nonzeros() == 4);
  const Box x{Interval(0.5, 0.6), Interval(1.5, 2.0)};
  std::vector<FastInterval> f(2), j(4);
  {
    RoundingGuard guard;
    c.evaluate(x, f.data(), j.data());
  }
  CHECK(f[1].lower() <= 1.5 - std::exp(0.6));
  CHECK(f[1].upper() >= 2.0 - std::exp(0.5));
  for (int e = 0; e < 4; ++e) {
    if (c.entry_row(e) != 1) continue;
    if (c.entry_col(e) == 1) CHECK((j[e].lower() == 1 && j[e].upper() == 1));
    if (c.entry_col(e) == 0) CHECK((j[e].lower() <= -std::exp(0.6) && j[e].upper() >= -std::exp(0.5)));
  }
  double y[2] = {0.5, 2.0}, ff[2], jf[4];
  c.values_float(y, ff);
  CHECK(ff[1] == Approx(2.0 - std::exp(0.5)));
  c.jacobian_float(y, jf);
  for (int e = 0; e < 4; ++e)
    if (c.entry_row(e) == 1 && c.entry_col(e) == 0) CHECK(jf[e] == Approx(-std::exp(0.5)));
}
