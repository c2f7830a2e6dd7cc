// In the peers' files a sum raised to a power is one unknown (model/lifting.hpp, "base"): the
// lifted system has the case's roots one to one (the same as the TOML twin, which expands),
// propagation sees through the cancellation that the expanded powers hide, and a sum that is
// only multiplied stays expanded (no idle unknown).
#include "formulate/load.hpp"
#include "input/expression.hpp"
#include "input/input_error.hpp"
#include "model/lifting.hpp"
#include "prune/hc4.hpp"
#include "tests/solved_case.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

using namespace linkbox;

namespace {

std::string polynomial_case(const std::string& variables, const std::string& equations) {
  return "kind = \"polynomial\"\nname = \"t\"\nvariables = [ " + variables + " ]\nequations = [ " + equations + " ]\n";
}

model::System lifted_system(const std::string& text, const std::string& file) {
  return formulate::load_case_text(text, file).formulation->subproblem(0).system;
}

bool near(const Box& b, double x, double y, double z) {
  return std::fabs(median(b[0]) - x) < 1e-9 && std::fabs(median(b[1]) - y) < 1e-9 && std::fabs(median(b[2]) - z) < 1e-9;
}

}  // namespace

TEST_CASE("power bases: a raised sum is one unknown, shared by its products", "[functions][power-bases]") {
  const std::string bch = R"~(Variables
  x in [-2, 2];
  y in [-2, 2];
  z in [-2, 2];
Constraints
  (x - y)^3 + exp(z)*(x - y) = 1;
  (x + y)*(x - y + z) = 2;
  z = 0.5;
end
)~";
  const model::System s = lifted_system(bch, "bases.bch");
  REQUIRE(s.lifting);
  // x, y, z, the base x - y, exp(z); (x + y) and (x - y + z) are only multiplied: expanded.
  REQUIRE(s.variables.size() == 5);
  CHECK(s.equations.size() == 4);  // three typed, b - (x - y) = 0
  CHECK(s.links.size() == 1);
  int bases = 0;
  for (const auto& src : s.lifting->sources)
    if (src.kind == model::Lifting::Source::Kind::application)
      bases += s.lifting->applications[src.index].function == model::Application::Function::base;
  CHECK(bases == 1);
  const Interval b = s.variables[3].domain;  // holds x - y over the domain
  CHECK((b.lower() <= -4 && b.upper() >= 4));

  // A monomial raised is not a sum; the TOML reader expands (its unknowns are its own).
  std::vector<model::Application> apps;
  input::parse_with_functions("(x*y)^3 + (x + 1)^2", {"x", "y"}, apps, nullptr, input::Powers::as_written);
  CHECK(apps.empty());
  input::parse_with_functions("(x - y)^3", {"x", "y"}, apps);
  CHECK(apps.empty());
}

TEST_CASE("power bases: propagation proves empty what the expanded power cannot", "[functions][power-bases]") {
  // (x - y)^3 = 1 has no root where |x - y| <= 2e-3; expanded near x = y = 200, the terms of
  // x^3 - 3x^2 y + 3x y^2 - y^3 each span hundreds, and their sum holds 1.
  const std::string bch = "Variables\n x in [199.999, 200.001];\n y in [199.999, 200.001];\n"
                          "Constraints\n (x - y)^3 = 1;\nend\n";
  const model::System s = lifted_system(bch, "cancel.bch");
  REQUIRE(s.variables.size() == 3);
  Box lifted = s.domain();
  prune::Hc4 hc4(s.equations, Arith::verified, s.inequalities, s.links);
  CHECK(hc4.contract(lifted) == prune::Outcome::empty);

  const model::Polynomial expanded = input::parse_polynomial("(x - y)^3 - 1", {"x", "y"});
  Box plain{Interval(199.999, 200.001), Interval(199.999, 200.001)};
  prune::Hc4 plain_hc4({expanded});
  CHECK(plain_hc4.contract(plain) != prune::Outcome::empty);
}

TEST_CASE("power bases: planted roots across an exponential's range, TOML and Minibex alike",
          "[functions][power-bases]") {
  // x - y = 0.1 (the cube is 0.001), x y = 2, exp(z) (x - y) = 0.1 so z = 0: two roots.
  const double r = std::sqrt(8.01);
  const double x1 = (0.1 + r) / 2, x2 = (0.1 - r) / 2;
  const std::string toml = polynomial_case(
      R"({ name = "x", domain = [-200, 200] }, { name = "y", domain = [-200, 200] }, { name = "z", domain = [-200, 200] })",
      R"("(x - y)^3 - 0.001", "x*y - 2", "exp(z)*(x - y) - 0.1")");
  const std::string bch = R"~(Variables
  x in [-200, 200];
  y in [-200, 200];
  z in [-200, 200];
Constraints
  (x - y)^3 = 0.001;
  x*y = 2;
  exp(z)*(x - y) = 0.1;
end
)~";
  for (const auto& [text, file] : {std::pair{toml, std::string("inline.toml")}, std::pair{bch, std::string("p.bch")}}) {
    INFO(file);
    const test::SolvedCase run = test::solve_loaded(formulate::load_case_text(text, file), "auto", 1e-6);
    CHECK(run.v.exact);
    REQUIRE(run.roots.size() == 2);
    CHECK((near(run.roots[0], x1, x1 - 0.1, 0) || near(run.roots[1], x1, x1 - 0.1, 0)));
    CHECK((near(run.roots[0], x2, x2 - 0.1, 0) || near(run.roots[1], x2, x2 - 0.1, 0)));
  }
}

TEST_CASE("power bases: a product of sums too large to expand is refused at its line", "[functions][power-bases]") {
  // 21 sums of two terms multiplied: 2^21 terms once expanded (each sum is only multiplied).
  std::string product = "(x + y)";
  for (int k = 1; k <= 20; ++k) product += "*(x + " + std::to_string(k + 1) + "*y)";
  const std::string bch = "Variables\n x in [0, 1];\n y in [0, 1];\nConstraints\n x = y;\n " + product + " = 1;\nend\n";
  try {
    formulate::load_case_text(bch, "big.bch");
    FAIL("read without error");
  } catch (const input::InputError& e) {
    CHECK(e.line == 6);
    CHECK(e.message.find("more than 1000000 terms") != std::string::npos);
  }
}
