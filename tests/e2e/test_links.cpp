// Functions that no polynomial relates to their argument (exp, log, sinh, ..., and sin or cos
// of a variable that also occurs outside them) as links y = f(a), and divisions by expressions
// with variables as q B = 1 (model/lifting.hpp): planted systems whose roots are known in
// closed form are solved, certified, re-checked, and substituted back in MPFI.
#include "input/input_error.hpp"
#include "interval/rigorous.hpp"
#include "tests/solved_case.hpp"
#include "verify/check.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>

using namespace linkbox;
using test::solve_text;

namespace {

std::string polynomial_case(const std::string& variables, const std::string& equations) {
  return "kind = \"polynomial\"\nname = \"t\"\nvariables = [ " + variables + " ]\nequations = [ " + equations + " ]\n";
}

// The certified roots, one coordinate each, hold `values` one to one.
void check_roots(const test::SolvedCase& run, const std::vector<std::vector<long double>>& values) {
  CHECK(run.v.exact);
  REQUIRE(run.roots.size() == values.size());
  for (auto& v : values) {
    int holding = 0;
    for (auto& r : run.roots) {
      bool all = true;
      for (size_t i = 0; i < v.size(); ++i) all = all && contains(r[i], static_cast<double>(v[i]));
      holding += all;
    }
    CHECK(holding == 1);
  }
  CHECK(verify::check_certificates(run.j, *run.c.formulation).failures.empty());
}

}  // namespace

TEST_CASE("exp(x) = 2: the certified root encloses ln 2", "[links]") {
  const auto run = solve_text(polynomial_case(R"~({ name = "x", domain = [-3, 3] })~", R"~("exp(x) - 2")~"), "hc4,newton", 1e-8);
  const auto& sys = run.c.formulation->subproblem(0).system;
  REQUIRE(sys.links.size() == 1);
  CHECK(sys.links[0].f == model::Elementary::exp);
  check_roots(run, {{logl(2.0L)}});
  CHECK(width(run.roots[0][0]) < 1e-12);
  // The links contractor ran first, and its counters are its own.
  REQUIRE(run.j.at("contractors").size() == 3);
  CHECK(run.j.at("contractors")[0].at("name") == "links");
  CHECK(run.j.at("contractors")[1].at("name") == "hc4");
}

TEST_CASE("log, sinh and an argument that is an expression", "[links]") {
  // log(x^2 + 1) = 1: x = +-sqrt(e - 1); the argument gets its own unknown and equation.
  const auto log = solve_text(polynomial_case(R"~({ name = "x", domain = [-3, 3] })~", R"~("log(x^2 + 1) = 1")~"));
  const auto& sys = log.c.formulation->subproblem(0).system;
  REQUIRE(sys.links.size() == 1);
  CHECK(sys.variables.size() == 3);  // x, log(...), its argument
  CHECK(sys.equations.size() == 2);  // y - 1, a - (x^2 + 1)
  const long double r = sqrtl(expl(1.0L) - 1);
  check_roots(log, {{r}, {-r}});
  // sinh(2x) + x = 1, with the argument 2x: x = 0.3287...
  const auto sinh = solve_text(polynomial_case(R"~({ name = "x", domain = [-2, 2] })~", R"~("sinh(2*x) + x = 1")~"));
  REQUIRE(sinh.roots.size() == 1);
  const double x = median(sinh.roots[0][0]);
  CHECK(std::fabs(std::sinh(2 * x) + x - 1) < 1e-12);
  check_roots(sinh, {{x}});
  // atan, tanh, asin, acos and cosh in one system: atan(x) = pi/4 - tanh(y - y) ... planted at
  // x = 1, y = 1/2: asin(y) = pi/6, acos(y) = pi/3, cosh(x - 1) = 1.
  const auto mixed = solve_text(polynomial_case(R"~({ name = "x", domain = [-2, 3] }, { name = "y", domain = [-1, 1] })~",
                                                R"~("atan(x) + asin(y) + tanh(x - 1) = pi/4 + pi/6", "acos(y) * cosh(x - 1) = pi/3")~"));
  check_roots(mixed, {{1.0L, 0.5L}});
}

TEST_CASE("sin of a variable that also occurs outside sin is a link", "[links]") {
  // sin(t) + t = 1: one root, t = 0.5109734293885691.
  const auto run = solve_text(polynomial_case(R"~({ name = "t", domain = [-2, 2] })~", R"~("sin(t) + t = 1")~"));
  REQUIRE(run.c.formulation->subproblem(0).system.links.size() == 1);
  REQUIRE(run.roots.size() == 1);
  const double t = median(run.roots[0][0]);
  CHECK(std::fabs(t - 0.5109734293885691) < 1e-12);
  check_roots(run, {{t}});
}

TEST_CASE("tan of a variable that also occurs outside tan is a link", "[links]") {
  // tan(t) + t = 1: one root, t = 0.479731007280409694724589799077 (mpmath).
  const auto run = solve_text(polynomial_case(R"~({ name = "t", domain = [-1.5, 1.5] })~", R"~("tan(t) + t = 1")~"));
  REQUIRE(run.c.formulation->subproblem(0).system.links.size() == 1);
  check_roots(run, {{0.479731007280409694724589799077L}});
  // On the next branch, through a new argument unknown: tan(t - 3) + t = 4 at t = 3.4797...
  const auto shifted = solve_text(polynomial_case(R"~({ name = "t", domain = [2, 4.5] })~", R"~("tan(t - 3) + t = 4")~"));
  check_roots(shifted, {{3.479731007280409694724589799077L}});
  // A non-affine argument, and one that is a function of the variables: links too.
  const auto squared = solve_text(polynomial_case(R"~({ name = "x", domain = [0, 1] })~", R"~("tan(x^2) - 0.5")~"));
  check_roots(squared, {{0.680916741607082323773933532663L}});  // sqrt(atan(1/2))
  const auto nested = solve_text(polynomial_case(R"~({ name = "x", domain = [0, 1] })~", R"~("tan(sqrt(x)) - 0.5")~"));
  check_roots(nested, {{0.214969105332164388710632716684L}});  // atan(1/2)^2
  // An argument whose range meets a pole is refused, naming it.
  try {
    formulate::load_case_text(polynomial_case(R"~({ name = "t", domain = [0, 2] })~", R"~("tan(t) + t = 1")~"),
                              "pole.toml");
    FAIL("read without error");
  } catch (const std::exception& e) {
    CHECK_THAT(e.what(), Catch::Matchers::Contains("meets a pole of tan"));
  }
}

TEST_CASE("a division by an expression with variables is q B = 1", "[links]") {
  // x/(y + 2) = 1 and x + y = 4: (3, 1); y + 2 is in [1, 7] on the domain.
  const auto run = solve_text(polynomial_case(R"~({ name = "x", domain = [0, 10] }, { name = "y", domain = [-1, 5] })~",
                                              R"~("x/(y + 2) = 1", "x + y = 4")~"));
  const auto& sys = run.c.formulation->subproblem(0).system;
  CHECK(sys.links.empty());  // polynomial: q (y + 2) = 1
  CHECK(sys.variables.size() == 3);
  check_roots(run, {{3.0L, 1.0L}});
  // A divisor that may vanish on the domain is cleared instead (test_divisions.cpp).
  const auto cleared = formulate::load_case_text(polynomial_case(R"~({ name = "x", domain = [-1, 1] })~", R"~("1/x = 2")~"),
                                                 "inline.toml");
  const auto& lifted = cleared.formulation->subproblem(0).system;
  CHECK(lifted.variables.size() == 1);
  CHECK(lifted.inequalities.size() == 1);
}

TEST_CASE("a small Bratu system: every certified root satisfies the equations in MPFI", "[links]") {
  // h exp(x_i) + x_(i-1) - 2 x_i + x_(i+1) = 0, i = 1..3, x_0 = x_4 = 0 (IbexSolve's Bratu
  // with three points). The Taylor relaxation reads the links' rows too.
  const std::string prune = GENERATE(as<std::string>{}, "hc4,newton", "hc4,newton,taylor");
  INFO(prune);
  const auto run = solve_text(polynomial_case(
      R"~({ name = "x1", domain = [-10, 20] }, { name = "x2", domain = [-10, 20] }, { name = "x3", domain = [-10, 20] })~",
      R"~("1/16*exp(x1) - 2*x1 + x2", "1/16*exp(x2) + x1 - 2*x2 + x3", "1/16*exp(x3) + x2 - 2*x3")~"),
      prune);
  CHECK(run.v.exact);
  REQUIRE(run.roots.size() >= 1);
  const Interval h = Interval(1.0) / Interval(16.0);
  for (auto& r : run.roots) {
    const Interval e1 = h * rigorous::exp(r[0]) - Interval(2.0) * r[0] + r[1];
    const Interval e2 = h * rigorous::exp(r[1]) + r[0] - Interval(2.0) * r[1] + r[2];
    const Interval e3 = h * rigorous::exp(r[2]) + r[1] - Interval(2.0) * r[2];
    CHECK(zero_in(e1));
    CHECK(zero_in(e2));
    CHECK(zero_in(e3));
    CHECK(width(r[0]) < 1e-9);
  }
  CHECK(verify::check_certificates(run.j, *run.c.formulation).failures.empty());
}

TEST_CASE("linkbox check re-proves a link's certificate and rejects a tampered one", "[links][check]") {
  const auto run = solve_text(polynomial_case(R"~({ name = "x", domain = [-3, 3] })~", R"~("exp(x) + x = 2")~"));
  REQUIRE(run.roots.size() == 1);
  CHECK(verify::check_certificates(run.j, *run.c.formulation).failures.empty());
  // The unknown y = exp(x) moved off the link in the certificate's box and image.
  nlohmann::json bad = run.j;
  for (auto& c : bad.at("clusters")) {
    if (c.at("status") != "certified") continue;
    for (const char* key : {"box", "image"}) {
      auto& side = c.at("certificate").at(key).at(1);
      side = {side.at(0).get<double>() + 0.01, side.at(1).get<double>() + 0.01};
    }
  }
  CHECK_FALSE(verify::check_certificates(bad, *run.c.formulation).failures.empty());
}
