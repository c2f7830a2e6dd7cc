// Divisions by expressions that may be 0 on the domain (model/lifting.hpp): the divisor is
// cleared (each equation and inequality multiplied by a power of it) and kept from 0 by a
// strict inequality, so the roots are the case's: none is lost, and a point where the
// divisor vanishes is never certified, even where the cleared equation has a simple root.
#include "input/input_error.hpp"
#include "tests/cli_run.hpp"
#include "tests/solved_case.hpp"
#include "verify/check.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

using namespace linkbox;
using test::solve_text;

namespace {

std::string polynomial_case(const std::string& variables, const std::string& equations,
                            const std::string& inequalities = "") {
  return "kind = \"polynomial\"\nname = \"t\"\nvariables = [ " + variables + " ]\nequations = [ " + equations +
         " ]\n" + (inequalities.empty() ? "" : "inequalities = [ " + inequalities + " ]\n");
}

// How many of `roots` hold the point.
int holding(const std::vector<Box>& roots, const std::vector<double>& p) {
  int n = 0;
  for (const Box& b : roots) {
    bool all = true;
    for (size_t i = 0; i < p.size(); ++i) all = all && contains(b[i], p[i]);
    n += all;
  }
  return n;
}

int certified_clusters(const test::SolvedCase& run) {
  int n = 0;
  for (auto& cl : run.v.clusters) n += cl.status == verify::ClusterStatus::certified;
  return n;
}

bool has_note(const test::SolvedCase& run, const std::string& part) {
  for (auto& n : run.c.formulation->model_notes())
    if (n.find(part) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("x/(x - 1) + y = 0 with y = 0: the root x = 0, the divisor cleared", "[divisions]") {
  // x - 1 ranges over [-1.5, 1] on the domain: the quotient is not bounded, so the equation
  // is multiplied by x - 1 (x + y (x - 1) = 0) and -(x - 1)^2 < 0 keeps the divisor from 0.
  const auto run = solve_text(polynomial_case(R"~({ name = "x", domain = [-0.5, 2] }, { name = "y", domain = [-1, 1] })~",
                                              R"~("x/(x - 1) + y = 0", "y = 0")~"));
  const auto& sys = run.c.formulation->subproblem(0).system;
  CHECK(sys.variables.size() == 2);  // no unknown for the quotient
  REQUIRE(sys.inequalities.size() == 1);
  CHECK(sys.inequalities[0].strict);
  CHECK(has_note(run, "cleared"));
  CHECK(run.v.exact);
  REQUIRE(run.roots.size() == 1);
  CHECK(holding(run.roots, {0.0, 0.0}) == 1);
  CHECK(verify::check_certificates(run.j, *run.c.formulation).failures.empty());
}

TEST_CASE("a root of the cleared equation where the divisor is 0 is never certified", "[divisions]") {
  // (6x - 2)/(3x - 1) = 2 for x != 1/3, so (6x - 2)/(3x - 1) = 1 has no real root. Cleared it
  // is 3x - 1 = 0, whose simple root 1/3 (not a double) interval Newton proves in a box where
  // 3x - 1 holds 0: the divisor's inequality is what keeps it from being counted. Its exact
  // point 1/3 (verify/exact_point.hpp) shows it violates that inequality: none, exactly.
  const auto simple = solve_text(polynomial_case(R"~({ name = "x", domain = [0, 1] })~", R"~("(6*x - 2)/(3*x - 1) = 1")~"));
  CHECK(simple.roots.empty());
  CHECK(certified_clusters(simple) == 0);
  bool violates = false;
  for (auto& cl : simple.v.clusters)
    violates = violates || (cl.status == verify::ClusterStatus::infeasible && cl.exact_root == std::vector<std::string>{"1/3"});
  CHECK(violates);
  CHECK(simple.v.exact);
  CHECK(simple.v.headline.find("exactly 0 roots") != std::string::npos);
  CHECK(verify::check_certificates(simple.j, *simple.c.formulation).failures.empty());

  // (x^2 - x)/(x - 1) = x for x != 1, so = 1 has no real root either; cleared: (x - 1)^2 = 0.
  const auto twice = solve_text(polynomial_case(R"~({ name = "x", domain = [0, 2] })~", R"~("(x^2 - x)/(x - 1) = 1")~"));
  CHECK(twice.roots.empty());
  CHECK(certified_clusters(twice) == 0);
}

TEST_CASE("divisors equal up to a constant factor are one unknown", "[divisions]") {
  // 2y + 2 = 2 (y + 1): both quotients are q = 1/(y + 1), and x/(2y + 2) is x q / 2.
  const auto run = solve_text(polynomial_case(R"~({ name = "x", domain = [0, 4] }, { name = "y", domain = [0, 4] })~",
                                              R"~("x/(2*y + 2) = 1/2", "3/(y + 1) = 1")~"));
  const auto& sys = run.c.formulation->subproblem(0).system;
  CHECK(sys.variables.size() == 3);  // x, y and one quotient
  CHECK(run.v.exact);
  REQUIRE(run.roots.size() == 1);
  CHECK(holding(run.roots, {3.0, 2.0}) == 1);
  // 3 + y is not 3 (1 + y/3) with an exact 1/3: its own unknown. The root: (3 + y)(1 + y) = 8.
  const auto inexact = solve_text(polynomial_case(R"~({ name = "y", domain = [0, 4] })~",
                                                  R"~("1/(3 + y) - 1/(1 + y) + 1/4 = 0")~"));
  CHECK(inexact.c.formulation->subproblem(0).system.variables.size() == 3);
  CHECK(inexact.v.exact);
  REQUIRE(inexact.roots.size() == 1);
  CHECK(holding(inexact.roots, {1.0}) == 1);
}

TEST_CASE("x^2/(x - 1) = 5: both roots, on either side of the pole", "[divisions]") {
  // x^2 - 5x + 5 = 0: x = (5 -+ sqrt 5)/2, 1.38 and 3.62, with the pole x = 1 between 0 and 4.
  const auto run = solve_text(polynomial_case(R"~({ name = "x", domain = [0, 4] })~", R"~("x^2/(x - 1) = 5")~"));
  CHECK(run.v.exact);
  REQUIRE(run.roots.size() == 2);
  CHECK(holding(run.roots, {(5 - std::sqrt(5.0)) / 2}) == 1);
  CHECK(holding(run.roots, {(5 + std::sqrt(5.0)) / 2}) == 1);
}

TEST_CASE("a rational inequality is multiplied by the divisor's square", "[divisions]") {
  // x^2 = 1/4 on [-1, 2]; x/(x - 1) <= 0 holds at 1/2 (-1) but not at -1/2 (1/3). Cleared:
  // x (x - 1) <= 0 and -(x - 1)^2 < 0.
  const auto run = solve_text(polynomial_case(R"~({ name = "x", domain = [-1, 2] })~", R"~("x^2 = 0.25")~",
                                              R"~("x/(x - 1) <= 0")~"));
  const auto& sys = run.c.formulation->subproblem(0).system;
  REQUIRE(sys.inequalities.size() == 2);
  CHECK(run.v.exact);
  REQUIRE(run.roots.size() == 1);
  CHECK(holding(run.roots, {0.5}) == 1);
}

TEST_CASE("nested divisors: 1/(1 + 1/x) = 1/2 is x = 1, never x = -1 or 0", "[divisions]") {
  // 1 + 1/x is unbounded on the domain, so both divisors are cleared: x - 1 = 0, with
  // -x^2 < 0 and -(x + 1)^2 < 0.
  const auto run = solve_text(polynomial_case(R"~({ name = "x", domain = [-2, 2] })~", R"~("1/(1 + 1/x) = 0.5")~"));
  CHECK(run.c.formulation->subproblem(0).system.inequalities.size() == 2);
  CHECK(run.v.exact);
  REQUIRE(run.roots.size() == 1);
  CHECK(holding(run.roots, {1.0}) == 1);
}

TEST_CASE("a TOML case and its Minibex twin with a divisor through 0 give the same roots", "[divisions][peer]") {
  // x = 2 (x - y) and x^2 + y^2 = 1: x = 2y, y = +-1/sqrt 5; x - y ranges over [-4, 4].
  const auto toml = solve_text(polynomial_case(R"~({ name = "x", domain = [-2, 2] }, { name = "y", domain = [-2, 2] })~",
                                               R"~("x/(x - y) = 2", "x^2 + y^2 = 1")~"));
  const std::string bch = "Variables\n  x in [-2, 2];\n  y in [-2, 2];\nConstraints\n  x/(x - y) = 2;\n"
                          "  x^2 + y^2 = 1;\nend\n";
  const auto peer = test::solve_loaded(formulate::load_case_text(bch, "twin.bch"), "hc4,newton", 1e-6);
  const double y = 1 / std::sqrt(5.0);
  for (const auto* run : {&toml, &peer}) {
    CHECK(run->v.exact);
    REQUIRE(run->roots.size() == 2);
    CHECK(holding(run->roots, {2 * y, y}) == 1);
    CHECK(holding(run->roots, {-2 * y, -y}) == 1);
  }
}

TEST_CASE("a function of a quotient whose divisor may be 0 is refused at its line", "[divisions][input]") {
  try {
    formulate::load_case_text(polynomial_case(R"~({ name = "x", domain = [-1, 1] })~", R"~("sqrt(1/x) = 2")~"),
                              "inline.toml");
    FAIL("loaded");
  } catch (const input::InputError& e) {
    CHECK(e.message.find("divisor that may be 0") != std::string::npos);
    CHECK(e.line == 4);
  }
}

TEST_CASE("IbexSolve's hayes1 and AOL-legentil are read", "[divisions][peer][cli]") {
  // The constraints of ibex-solver's benchmarks others/hayes1.bch and non-polynom/AOL-legentil.bch
  // (divisors 1 + a1 s + a2 s^2 and 3.5 - 5 sin(y) reach 0 on their domains).
  const std::string hayes1 = R"~(Constants
b0=2;
Variables
a1 in [-0.9,-0.7];
a2 in [-0.03,-0.01];
b1 in [-2.7,-2.6];
b2 in [0.7,0.8];
s4 in [1.35,1.45];
s5 in [6.9,7];
s6 in [1.15,1.25];
Constraints
52 - (90*(b0 + b1 + b2))/(1 + a1 + a2) = 0;
90 - (30*(b0 - b1 + b2))/(1 - a1 + a2) = 0;
58 - (41*(b0 + b1*s4 + b2*s4^2))/(1 + a1*s4 + a2*s4^2) = 0;
(-159600*(-1 - s4))/(1 - a1 + a2) - (2803905*(1 - s4))/(8*(1 + a1 + a2)) - (3080337*s4)/8 - (54944*(-s4 + s6))/(1 + a1*s6 + a2*s6^2) = 0;
(-89760*(-1 - s4))/(1 - a1 + a2) + (7312635*(1 - s4))/(32*(1 + a1 + a2)) + (7677115*s4)/32 - (99586*(-s4 + s5))/(1 + a1*s5 + a2*s5^2) = 0;
(-2803905*(1 - s4))/(4*(1 + a1 + a2)) - (3080337*s4)/8 - (54944*(1 + s6)*(-s4 + s6))/(1 + a1*s6 + a2*s6^2) = 0;
(7312635*(1 - s4))/(16*(1 + a1 + a2)) + (7677115*s4)/32 - (99586*(1 + s5)*(-s4 + s5))/(1 + a1*s5 + a2*s5^2) = 0;
end
)~";
  const std::string aol = R"~(Variables
x in [1e-10,pi/2-1e-10];
y in [0,pi/2-1e-10];
z in [-1e8, 1e8];
Constraints
10/3*cos(x)/sin(x)^2+4*(1+tan(x)^2)/cos(y)+z*(-50/3*sin(y)*cos(x)/(sin(x)^2*(3.5-5*sin(y)))-10/3*cos(x)/sin(x)^2-4*(1+tan(x)^2)/cos(y))=0;
4*tan(x)*sin(y)/cos(y)^2+z*(50/3*cos(y)/(sin(x)*(3.5-5*sin(y)))+250/3*sin(y)*cos(y)/(sin(x)*(3.5-5*sin(y))^2)-4*tan(x)*sin(y)/cos(y)^2)=0;
50/3*sin(y)/(sin(x)*(3.5-5*sin(y)))+20+10/3/sin(x)-4*tan(x)/cos(y)=0;
end
)~";
  for (auto [name, text] : {std::pair{"hayes1.bch", hayes1}, std::pair{"AOL-legentil.bch", aol}}) {
    INFO(name);
    const std::string path = test::scratch(name);
    std::ofstream(path) << text;
    const test::Ran ran = test::run_cli("solve " + path + " --max-boxes 1 --no-verify --quiet");
    INFO(ran.out);
    CHECK(ran.code != 2);
    const auto c = formulate::load_case_text(text, name);
    bool cleared = false;
    for (auto& n : c.formulation->model_notes()) cleared = cleared || n.find("cleared") != std::string::npos;
    CHECK(cleared);
  }
}
