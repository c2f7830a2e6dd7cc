// Exact coefficients (model/exact_coefficients.hpp): a decimal's value as written travels
// beside its interval through sums, products, quotients and powers, each checked against
// rationals computed apart; and whatever has no exact rational value is never given one.
#include "input/expression.hpp"
#include "model/exact_coefficients.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace linkbox;
using model::Polynomial;
using model::Rational;

namespace {

const std::vector<std::string> kNames{"x", "y"};

Polynomial parse(const std::string& text) {
  std::vector<model::Application> applications;
  input::IntervalConstants intervals;
  return input::parse_with_functions(text, kNames, applications, &intervals);
}

std::optional<Rational> coefficient(const Polynomial& p, const model::Powers& powers) {
  auto it = p.terms().find(powers);
  if (it == p.terms().end()) return Rational(0);
  return model::exact_coefficient(p, powers, it->second);
}

Rational q(long n, long d = 1) { return Rational(n) / Rational(d); }

// The interval holds its exact value: lower <= q <= upper, compared exactly.
bool encloses(const Interval& c, const Rational& value) { return Rational(c.lower()) <= value && value <= Rational(c.upper()); }

}  // namespace

TEST_CASE("a decimal literal is read as the rational it writes", "[model][exact]") {
  CHECK(model::exact_decimal("0.1") == q(1, 10));
  CHECK(model::exact_decimal("1.5e-3") == q(3, 2000));
  CHECK(model::exact_decimal("2E+2") == q(200));
  CHECK(model::exact_decimal(".25") == q(1, 4));
  CHECK(model::exact_decimal("12") == q(12));
  CHECK(model::exact_decimal("0.012") == q(3, 250));
  CHECK(model::exact_decimal("0009.0") == q(9));
  CHECK(model::exact_decimal("0.0") == q(0));
  CHECK_FALSE(model::exact_decimal("1e"));
  CHECK_FALSE(model::exact_decimal("1e99999"));
  CHECK_FALSE(model::exact_decimal("0.1x"));
  CHECK_FALSE(model::exact_decimal(""));
}

TEST_CASE("a rational's enclosure is the tightest interval of doubles around it", "[model][exact]") {
  for (const Rational& value : {q(1, 10), q(-1, 3), q(3), q(-7, 1024), q(1, 1000000007)}) {
    const Interval e = model::enclosure(value);
    CHECK(encloses(e, value));
    CHECK((e.lower() == e.upper() || std::nextafter(e.lower(), 1e300) == e.upper()));
  }
  CHECK(model::enclosure(q(3)).lower() == 3);
  CHECK(model::enclosure(q(3)).upper() == 3);
}

TEST_CASE("an exact cancellation leaves no term, where intervals leave a width around 0", "[model][exact]") {
  const Polynomial p = parse("(0.3 + 0.1*x)^2 - 0.09 - 0.06*x");
  CHECK(p.terms().size() == 1);  // only 0.01 x^2
  CHECK(coefficient(p, {{0, 2}}) == q(1, 100));
}

TEST_CASE("a decimal's exact value survives the parser's arithmetic", "[model][exact]") {
  const Polynomial p = parse("(0.3 + 0.1*x - 0.1*y)^2 - 0.09");
  CHECK(coefficient(p, {}) == q(0));
  CHECK(coefficient(p, {{0, 1}}) == q(3, 50));
  CHECK(coefficient(p, {{0, 1}, {1, 1}}) == q(-1, 50));
  CHECK(coefficient(p, {{1, 2}}) == q(1, 100));
  CHECK(coefficient(parse("x/3"), {{0, 1}}) == q(1, 3));
  CHECK(coefficient(parse("x/0.3"), {{0, 1}}) == q(10, 3));
  CHECK(coefficient(parse("0.1^3*y"), {{1, 1}}) == q(1, 1000));
  CHECK(coefficient(parse("-(0.7*x)"), {{0, 1}}) == q(-7, 10));
  CHECK(coefficient(parse("0.1*x - x/10"), {{0, 1}}) == q(0));
  CHECK(coefficient(parse("0.1*x^2").derivative(0), {{0, 1}}) == q(1, 5));
  CHECK(coefficient(parse("x*0.5 + 0.25"), {}) == q(1, 4));  // doubles are their own values
}

TEST_CASE("a constant with no exact rational value is never given one", "[model][exact]") {
  CHECK_FALSE(coefficient(parse("pi*x"), {{0, 1}}));
  CHECK_FALSE(coefficient(parse("0.1*pi*x"), {{0, 1}}));
  CHECK_FALSE(coefficient(parse("sqrt(2)*x"), {{0, 1}}));
  CHECK_FALSE(coefficient(parse("[0.1, 0.2]*x"), {{0, 1}}));
  CHECK_FALSE(coefficient(parse("x/pi"), {{0, 1}}));
  CHECK_FALSE(coefficient(parse("(0.1*x + 1)*sin(1)"), {{0, 1}}));
  Polynomial p = parse("0.1*x");
  p *= Interval(0.9, 1.1);
  CHECK_FALSE(coefficient(p, {{0, 1}}));
}

TEST_CASE("random decimal arithmetic: each enclosure holds the exact value kept beside it", "[model][exact]") {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> digits(1, 999), exponent(-6, 3), sign(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    std::string literal[3];
    Rational value[3];
    for (int k = 0; k < 3; ++k) {
      literal[k] = std::string(sign(rng) ? "-" : "") + std::to_string(digits(rng)) + "e" + std::to_string(exponent(rng));
      value[k] = *model::exact_decimal(literal[k].substr(literal[k][0] == '-')) * (literal[k][0] == '-' ? -1 : 1);
    }
    const std::string a = "(" + literal[0] + ")", b = "(" + literal[1] + ")", c = "(" + literal[2] + ")";
    const Polynomial p = parse(a + "*" + b + "*x^2 + " + a + "/" + b + "*x*y - (" + c + "*y + " + a + ")^2");
    const std::vector<std::pair<model::Powers, Rational>> expected{
        {{{0, 2}}, value[0] * value[1]},
        {{{0, 1}, {1, 1}}, value[0] / value[1]},
        {{{1, 2}}, -value[2] * value[2]},
        {{{1, 1}}, -2 * value[2] * value[0]},
        {{}, -value[0] * value[0]}};
    for (auto& [powers, exact] : expected) {
      INFO(a << " " << b << " " << c);
      REQUIRE(coefficient(p, powers) == exact);
      auto it = p.terms().find(powers);
      if (it == p.terms().end()) continue;
      CHECK(encloses(it->second, exact));
      const Interval tight = model::enclosure(exact);  // at most one ulp wide
      CHECK((it->second.lower() == tight.lower() && it->second.upper() == tight.upper()));
    }
  }
}

TEST_CASE("functions of decimals alike to 17 digits are two applications, not one", "[model][exact]") {
  std::vector<model::Application> applications;
  input::parse_with_functions("sin(0.1*x) + sin(0.1000000000000000000001*x) + sin(0.1*x)", kNames, applications);
  CHECK(applications.size() == 2);
}
