#include "interval/rigorous.hpp"
#include "input/expression.hpp"

#include <catch2/catch.hpp>

#include <string>

using namespace linkbox;
using input::parse_constant;
using input::parse_polynomial;
using model::Polynomial;

namespace {

const std::vector<std::string> kXY = {"x", "y"};

bool same(const Interval& a, const Interval& b) { return a.lower() == b.lower() && a.upper() == b.upper(); }

bool point(const Interval& a, double v) { return a.lower() == v && a.upper() == v; }

// Coefficient of the monomial with the given powers (0 when absent).
Interval coefficient(const Polynomial& p, const model::Powers& powers) {
  auto it = p.terms().find(powers);
  return it == p.terms().end() ? Interval(0.0) : it->second;
}

// Column of the ParseError `text` raises (-1 when it parses).
int error_column(const std::string& text, const std::vector<std::string>& vars = kXY) {
  try {
    parse_polynomial(text, vars);
  } catch (const input::ParseError& e) {
    return e.column;
  }
  return -1;
}

std::string error_message(const std::string& text, const std::vector<std::string>& vars = kXY) {
  try {
    parse_polynomial(text, vars);
  } catch (const input::ParseError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("expression: polynomial terms", "[expression]") {
  const Polynomial p = parse_polynomial("x^2 + y^2 - 1", kXY);
  CHECK(p.terms().size() == 3);
  CHECK(point(coefficient(p, {{0, 2}}), 1));
  CHECK(point(coefficient(p, {{1, 2}}), 1));
  CHECK(point(coefficient(p, {}), -1));

  const Polynomial q = parse_polynomial("(x + 1)^2 - (x - y)*(x + y)", kXY);  // 2x + 1 + y^2
  CHECK(q.terms().size() == 3);
  CHECK(point(coefficient(q, {{0, 1}}), 2));
  CHECK(point(coefficient(q, {{1, 2}}), 1));
  CHECK(point(coefficient(q, {}), 1));

  CHECK(parse_polynomial("x - x", kXY).is_zero());
  CHECK(parse_polynomial("y", kXY).variables() == std::vector<int>{1});
}

TEST_CASE("expression: precedence and associativity", "[expression]") {
  CHECK(point(parse_constant("-2^2"), -4));  // unary minus binds looser than ^
  CHECK(point(parse_constant("2^3^2"), 512));
  CHECK(point(parse_constant("1 - 2 - 3"), -4));
  CHECK(point(parse_constant("8 / 4 / 2"), 1));
  CHECK(point(parse_constant("2 + 3 * 4"), 14));
  CHECK(point(parse_constant("(2 + 3) * 4"), 20));
  CHECK(point(parse_constant("--3"), 3));
  CHECK(point(parse_constant("+3"), 3));
  CHECK(point(parse_constant("0^0"), 1));
  CHECK(point(coefficient(parse_polynomial("-x^2", kXY), {{0, 2}}), -1));
  CHECK(point(coefficient(parse_polynomial("x^(4/2)", kXY), {{0, 2}}), 1));
  CHECK(point(coefficient(parse_polynomial("x^2.0", kXY), {{0, 2}}), 1));
  CHECK(parse_polynomial("x^0", kXY).is_constant());
}

TEST_CASE("expression: numbers are enclosed as the decimals written", "[expression]") {
  CHECK(same(parse_constant("0.0175"), rigorous::decimal("0.0175")));
  CHECK(parse_constant("0.0175").lower() < parse_constant("0.0175").upper());  // not a double
  CHECK(point(parse_constant(".5"), 0.5));
  CHECK(point(parse_constant("1."), 1));
  CHECK(point(parse_constant("1e3"), 1000));
  CHECK(point(parse_constant("2.5E+2"), 250));
  CHECK(contains(parse_constant("1e-7"), 1e-7));
  const Interval c = coefficient(parse_polynomial("0.0175*x", kXY), {{0, 1}});
  CHECK(same(c, rigorous::decimal("0.0175")));
  const Interval minus = parse_constant("-0.7448995469549714");
  CHECK(same(minus, -rigorous::decimal("0.7448995469549714")));
}

TEST_CASE("expression: constants and functions fold rigorously", "[expression]") {
  const Interval half_pi = parse_constant("pi/2");
  CHECK(contains(half_pi, 1.5707963267948966));
  CHECK(half_pi.lower() < half_pi.upper());
  CHECK(contains(parse_constant("cos(pi/3)"), 0.5));
  CHECK(contains(parse_constant("sin(pi/6)*2"), 1.0));
  CHECK(contains(parse_constant("acos(-1/3)"), 1.9106332362490186));
  CHECK(contains(parse_constant("sqrt(2)^2"), 2.0));
  CHECK(contains(parse_constant("exp(log(3))"), 3.0));
  CHECK(contains(parse_constant("tan(atan(0.5))"), 0.5));
  CHECK(contains(parse_constant("asin(1)"), 1.5707963267948966));
  CHECK(width_up(parse_constant("acos(-1/3)")) < 1e-15);
  // 3^40 is not a double: the power is an enclosure, not a rounded point.
  const Interval big = parse_constant("3^40"), exact = rigorous::decimal("12157665459056928801");
  CHECK(big.lower() < big.upper());
  CHECK((big.lower() <= exact.lower() && exact.upper() <= big.upper()));
  CHECK(contains(parse_constant("(1/3)^3") * Interval(27.0), 1.0));
  // A coefficient divided by a constant is divided directly: x/3 is the enclosure of 1/3.
  CHECK(same(coefficient(parse_polynomial("x/3", kXY), {{0, 1}}), Interval(1.0) / Interval(3.0)));
  // Variables may shadow the constant pi.
  CHECK(parse_polynomial("pi", {"pi"}).variables() == std::vector<int>{0});
}

TEST_CASE("expression: errors carry the column", "[expression]") {
  CHECK(error_column("") == 0);
  CHECK(error_column("   ") == 0);
  CHECK(error_column("x + * y") == 4);
  CHECK(error_column("z + x") == 0);
  CHECK(error_message("x + z") == "unknown variable 'z'");
  CHECK(error_column("x + z") == 4);
  CHECK(error_column("(x + 1") == 6);
  CHECK(error_message("(x + 1").find("missing ')'") != std::string::npos);
  CHECK(error_column("x + 1)") == 5);
  CHECK(error_message("x + 1)") == "unmatched ')'");
  CHECK(error_column("x $ y") == 2);
  CHECK(error_message("x $ y").find("unexpected character '$'") != std::string::npos);
  CHECK(error_column("2x") == 1);
  CHECK(error_column("x y") == 2);
  CHECK(error_column("1e+") == 0);
}

TEST_CASE("expression: exponents are non-negative integers", "[expression]") {
  const std::string message = "exponent must be a non-negative integer constant";
  CHECK(error_message("x^2.5") == message);
  CHECK(error_column("x^2.5") == 2);
  CHECK(error_message("x^-1") == message);
  CHECK(error_message("x^y") == message);
  CHECK(error_message("x^(1/3)") == message);
  CHECK(error_message("x^pi") == message);
  CHECK(error_message("x^100000").find("larger than") != std::string::npos);
}

TEST_CASE("expression: functions apply to constants only", "[expression]") {
  CHECK(error_column("1 + sin(x)") == 4);
  CHECK(error_message("1 + sin(x)").find("functions apply to constants only") != std::string::npos);
  CHECK(error_message("cos(x - x)").find("constants only") != std::string::npos);  // syntactic
  CHECK(error_message("sin").find("needs a parenthesised argument") != std::string::npos);
  CHECK(error_message("foo(1)") == "unknown function 'foo'");
  CHECK(error_message("asin(2)").find("asin:") == 0);
  CHECK(error_message("log(0)").find("log:") == 0);
  CHECK(error_message("sqrt(-1)").find("sqrt:") == 0);
  CHECK(error_column("2 * log(-1)") == 4);
}

TEST_CASE("expression: division only by constants away from zero", "[expression]") {
  CHECK(error_message("1/0") == "division by an interval containing zero");
  CHECK(error_column("1/0") == 2);
  CHECK(error_message("x/(pi - pi)") == "division by an interval containing zero");  // [-eps, eps]
  CHECK(error_message("1/x").find("division by an expression with variables") == 0);  // parse_polynomial
  std::vector<model::Application> apps;
  const model::Polynomial q = input::parse_with_functions("(x + 1)/(x^2 + 1) + 2/x", {"x"}, apps);
  REQUIRE(apps.size() == 2);  // 1/(x^2 + 1), 1/x
  CHECK(apps[0].function == model::Application::Function::reciprocal);
  CHECK(apps[0].text == "1/(x^2 + 1)");
  CHECK(apps[1].text == "1/x");
  CHECK(q.variables() == std::vector<int>{0, 1, 2});  // x * q0, q0, q1
  CHECK(contains(parse_constant("1/3") * Interval(3.0), 1.0));
}

TEST_CASE("expression: NaN, infinity and overflow are rejected", "[expression]") {
  CHECK(error_message("nan").find("must be finite") != std::string::npos);
  CHECK(error_message("x + inf").find("must be finite") != std::string::npos);
  CHECK(error_message("-Infinity").find("must be finite") != std::string::npos);
  CHECK(error_message("1e400").find("outside the range") != std::string::npos);
  CHECK(error_message("1e300 * 1e300").find("not finite") != std::string::npos);
  CHECK(error_message("exp(1000)").find("not finite") != std::string::npos);
  CHECK(error_message("10^400").find("not finite") != std::string::npos);
  CHECK_NOTHROW(parse_constant("1e-400"));  // underflow is a valid enclosure [0, tiny]
}

TEST_CASE("expression: hostile inputs fail cleanly", "[expression]") {
  CHECK(error_message(std::string(100000, '(') + "1").find("nested too deeply") != std::string::npos);
  CHECK(error_message(std::string(100000, '-') + "1").find("nested too deeply") != std::string::npos);
  CHECK(error_message("(x + y + 1)^1000 * (x - y + 3)^1000").find("too many terms") != std::string::npos);
  CHECK(error_column(std::string("x\0y", 3)) == 1);
  CHECK(error_column("x + \xC3\xA9") == 4);
  CHECK_THROWS_AS(parse_constant("x"), input::ParseError);
}

TEST_CASE("expression: variable names usable in equations", "[expression]") {
  CHECK(input::is_valid_variable_name("t_1"));
  CHECK(input::is_valid_variable_name("_a"));
  CHECK_FALSE(input::is_valid_variable_name("1t"));
  CHECK_FALSE(input::is_valid_variable_name("a b"));
  CHECK_FALSE(input::is_valid_variable_name("pi"));
  CHECK_FALSE(input::is_valid_variable_name("sin"));
  CHECK_FALSE(input::is_valid_variable_name("nan"));
  CHECK_FALSE(input::is_valid_variable_name(""));
}
