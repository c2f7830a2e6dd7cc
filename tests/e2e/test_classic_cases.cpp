// Classic systems of cases/classic/ (papers/reliability/classic.md) whose answers are known
// independently of linkbox.
#include "formulate/load.hpp"
#include "tests/solved_case.hpp"
#include "verify/check.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

using namespace linkbox;

// Morgan's combustion system: unknowns near 1e-5 to 1e-11, coefficients down to 1e-15, so its
// Jacobian's plain reciprocal condition is far below the singular threshold although every
// root is regular. Equations 4 and 7 alone give x4 in closed form: 2 x4^2 / a7 + x4 = 1e-5.
TEST_CASE("classic: the combustion system's four roots certify despite its scaling", "[classic]") {
  auto run = test::solve_loaded(formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/cases/classic/combustion.bch"),
                                "hc4,newton/lp", 1e-4);
  CHECK(run.v.exact);
  REQUIRE(run.roots.size() == 4);
  const double a7 = 0.7816278e-15, d = std::sqrt(1 + 8e-5 / a7);
  for (double x4 : {(-1 + d) * a7 / 4, (-1 - d) * a7 / 4}) {
    int holding = 0;
    for (const Box& r : run.roots) holding += r[3].lower() <= x4 + 1e-12 * std::fabs(x4) && x4 - 1e-12 * std::fabs(x4) <= r[3].upper();
    CHECK(holding == 2);
  }
  CHECK(verify::check_certificates(run.j, *run.c.formulation).failures.empty());
}

namespace {

std::string beale(const std::string& third_constant) {
  return "Variables\nx1 in [-10,10];\nx2 in [-10,10];\nConstraints\n1.5 - x1*(1 - x2) = 0;\n"
         "2.25 - x1*(1 - x2^2) = 0;\n" + third_constant + " - x1*(1 - x2^3) = 0;\nend\n";
}

}  // namespace

// Beale's three equations in two unknowns have the one root (3, 1/2). The two first equations
// certify it; the third is exactly 0 there, which makes it a root of all three. With the third
// constant moved by 2^-51 (one ulp) the third equation still contains 0 over the certified box but is
// not 0 at the root: no root then, and nothing may be certified.
TEST_CASE("classic: an overdetermined system's exact root is certified, a near miss is not", "[classic]") {
  auto run = test::solve_loaded(formulate::load_case_text(beale("2.625"), "beale.bch"), "hc4,newton", 1e-8);
  CHECK(run.v.exact);
  REQUIRE(run.roots.size() == 1);
  CHECK((run.roots[0][0].lower() <= 3 && 3 <= run.roots[0][0].upper()));
  CHECK((run.roots[0][1].lower() <= 0.5 && 0.5 <= run.roots[0][1].upper()));
  CHECK(verify::check_certificates(run.j, *run.c.formulation).failures.empty());
  nlohmann::json forged = run.j;
  int forged_roots = 0;
  for (auto& c : forged.at("clusters"))
    if (c.value("argument", "") == "exact root") c["exact_root"] = {"3", "1/3"}, ++forged_roots;
  REQUIRE(forged_roots == 1);
  CHECK_FALSE(verify::check_certificates(forged, *run.c.formulation).failures.empty());

  auto near = test::solve_loaded(formulate::load_case_text(beale("(2.625 + 2^-51)"), "near.bch"), "hc4,newton", 1e-8);
  CHECK(near.roots.empty());
  CHECK_FALSE(near.v.exact);
}

namespace {

// Beale with its first equation written `first` (1.5 - x1*(1 - x2) = 0 scaled or rewritten).
std::string beale_first(const std::string& first, const std::string& third_constant = "2.625") {
  std::string text = beale(third_constant);
  const std::string from = "1.5 - x1*(1 - x2) = 0;";
  return text.replace(text.find(from), from.size(), first);
}

int reasons_with(const test::SolvedCase& run, const std::string& words) {
  int n = 0;
  for (auto& c : run.v.clusters) n += c.reason.find(words) != std::string::npos;
  return n;
}

}  // namespace

// Beale with its first equation divided by 10: 0.15 and 0.1 are intervals around the decimals
// for the search, and their values as written are kept beside them, so the root is exact as
// before. A third constant written one decimal digit past 2.625, inside the same double
// interval, must not be: its exact value is not 2.625.
TEST_CASE("classic: decimal coefficients keep their exact values, so an overdetermined root is certified", "[classic]") {
  const std::string decimal = "0.15 - 0.1*x1*(1 - x2) = 0;";
  auto run = test::solve_loaded(formulate::load_case_text(beale_first(decimal), "beale-decimal.bch"), "hc4,newton", 1e-8);
  CHECK(run.v.exact);
  REQUIRE(run.roots.size() == 1);
  CHECK(verify::check_certificates(run.j, *run.c.formulation).failures.empty());
  const std::string near_text = beale_first(decimal, "2.6250000000000000001");
  auto near = test::solve_loaded(formulate::load_case_text(near_text, "near-decimal.bch"), "hc4,newton", 1e-8);
  CHECK(near.roots.empty());
  CHECK_FALSE(near.v.exact);
  CHECK(reasons_with(near, "no exact value") == 0);
}

// sqrt(0.0225) is 0.15, but its enclosure has no exact rational value beside it: the root stays a
// candidate, and the cluster says why.
TEST_CASE("classic: a coefficient with no exact value leaves an overdetermined root a candidate, and says why", "[classic]") {
  const std::string text = beale_first("sqrt(0.0225) - 0.1*x1*(1 - x2) = 0;");
  auto run = test::solve_loaded(formulate::load_case_text(text, "beale-sqrt.bch"), "hc4,newton", 1e-8);
  CHECK(run.roots.empty());
  CHECK_FALSE(run.v.exact);
  CHECK(reasons_with(run, "no exact root can be placed: some coefficients have no exact value") == 1);
}
