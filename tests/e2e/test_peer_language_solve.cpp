// Minibex cases that use the whole polynomial-case language, solved: functions of variables
// and inequalities give the roots their TOML twin gives, and interval constants give roots
// certified for every value of the constants (planted families whose roots are known in
// closed form for each value), never a count where the family's count changes.
#include "input/input_error.hpp"
#include "input/to_toml.hpp"
#include "tests/cli_run.hpp"
#include "tests/solved_case.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

using namespace linkbox;

namespace {

test::SolvedCase solve_peer(const std::string& text, const std::string& file, double sigma) {
  return test::solve_loaded(formulate::load_case_text(text, file), "hc4,newton", sigma);
}

bool contains_point(const Box& box, const std::vector<double>& p) {
  for (size_t i = 0; i < p.size(); ++i)
    if (!(box[i].lower() <= p[i] && p[i] <= box[i].upper())) return false;
  return true;
}

// How many of `roots` hold the point.
int holding(const std::vector<Box>& roots, const std::vector<double>& p) {
  int n = 0;
  for (const Box& b : roots) n += contains_point(b, p);
  return n;
}

}  // namespace

TEST_CASE("peer language: a .bch with sin, cos and an inequality solves as its TOML twin", "[peer][functions]") {
  // cos t = 1/2 at t = +-pi/3; then x^2 = 2 + 2 sin t: x = sqrt(2 + sqrt 3) or sqrt(2 - sqrt 3).
  const std::string bch = R"~(Variables
  t in [-3, 3];
  x in [0, 2];
Constraints
  2*cos(t) = 1;
  x^2 = 2*sin(t) + 2;
end
)~";
  const test::SolvedCase peer = solve_peer(bch, "angles.bch", 1e-6);
  CHECK(peer.v.exact);
  REQUIRE(peer.roots.size() == 2);
  const double pi3 = std::acos(0.5);
  CHECK(holding(peer.roots, {pi3, std::sqrt(2 + std::sqrt(3.0))}) == 1);
  CHECK(holding(peer.roots, {-pi3, std::sqrt(2 - std::sqrt(3.0))}) == 1);
  const test::SolvedCase twin = test::solve_text(input::convert_text_to_toml(bch, "angles.bch"));
  CHECK(twin.roots.size() == 2);

  const std::string elbow = bch.substr(0, bch.find("end")) + "  x > 1;\nend\n";
  const test::SolvedCase one = solve_peer(elbow, "elbow.bch", 1e-6);
  CHECK(one.v.exact);
  CHECK(one.roots.size() == 1);
  CHECK(one.v.headline.find("where the inequalities hold") != std::string::npos);
}

TEST_CASE("peer language: abs, min, max, sign and pow read as IbexSolve reads them", "[peer][functions]") {
  // Where x >= y, the first gives y = 1 - x, and then the second 1/x - x = 1/0.7 - 0.7: x = 0.7.
  // Where y > x, y = 1/2 and 1/x + x = 1/0.7 - 0.7 has no root. So (0.7, 0.3) alone.
  const std::string bch = R"~(Variables
  x in [0.1, 3];
  y in [0.05, 1];
Constraints
  max(x, y) + abs(y) = 1;
  pow(x, -1) + min(x, y) - sign(y) = 1/0.7 + 0.3 - 1;
end
)~";
  const test::SolvedCase peer = solve_peer(bch, "piecewise.bch", 1e-6);
  CHECK(peer.v.exact);
  REQUIRE(peer.roots.size() == 1);
  CHECK(holding(peer.roots, {0.7, 0.3}) == 1);
  bool refused = false;
  try {
    formulate::load_case_text("Variables\n x in [0, 1];\nConstraints\n max(x) = 1;\nend\n", "one.bch");
  } catch (const input::InputError& e) {
    refused = e.line == 4 && std::string(e.message).find("max") != std::string::npos;
  }
  CHECK(refused);
}

TEST_CASE("peer language: atan2 and the inverse hyperbolic functions read as IbexSolve reads them",
          "[peer][functions]") {
  // A root planted on the circle of radius 2 at the angle 2 (x = 2 cos 2, y = 2 sin 2); other
  // points of the circle may solve it too.
  const double x = 2 * std::cos(2.0), y = 2 * std::sin(2.0);
  std::ostringstream bch;
  bch.precision(17);
  bch << "Variables\n  x in [-3, 3];\n  y in [-3, 3];\nConstraints\n  x^2 + y^2 = 4;\n"
      << "  atan2(y, x) + acosh(2 + y^2) - atanh(x/5) = " << 2 + std::acosh(2 + y * y) - std::atanh(x / 5) << ";\nend\n";
  const test::SolvedCase peer = solve_peer(bch.str(), "angle.bch", 1e-6);
  CHECK(peer.v.exact);
  REQUIRE(peer.roots.size() >= 1);
  CHECK(holding(peer.roots, {x, y}) == 1);
}

TEST_CASE("interval constants: planted families keep their roots for every value", "[peer][interval-constants]") {
  // x + y = 3, x y = c: x = (3 -+ sqrt(9 - 4c))/2 for every c in [1.9, 2.1].
  const std::string bch = R"~(Constants
  c in [1.9, 2.1];
Variables
  x in [-5, 5];
  y in [-5, 5];
Constraints
  x + y = 3;
  x*y = c;
end
)~";
  const test::SolvedCase run = solve_peer(bch, "family.bch", 1e-3);
  CHECK(run.v.exact);
  CHECK(run.v.headline.rfind("exactly 2 roots in the domain for every value of the interval constants", 0) == 0);
  CHECK(run.j["verification"]["interval_constants"] == nlohmann::json::array({"[1.9, 2.1]"}));
  REQUIRE(run.roots.size() == 2);
  // Each certified box holds the root for every value of c (ends and inside), and the two
  // roots of one value lie in different boxes.
  for (int k = 0; k <= 20; ++k) {
    const double c = 1.9 + 0.2 * k / 20, d = std::sqrt(9 - 4 * c);
    INFO("c = " << c);
    const std::vector<double> low{(3 - d) / 2, (3 + d) / 2}, high{(3 + d) / 2, (3 - d) / 2};
    CHECK(holding(run.roots, low) == 1);
    CHECK(holding(run.roots, high) == 1);
    CHECK(contains_point(run.roots[0], low) != contains_point(run.roots[0], high));
  }
}

TEST_CASE("interval constants: where the count changes within the family, none is claimed",
          "[peer][interval-constants]") {
  // x^2 = c with c in [-1, 1]: no root for c < 0, one double root at 0, two for c > 0.
  const test::SolvedCase run =
      solve_peer("Constants c in [-1, 1]; Variables x in [-2, 2]; Constraints x^2 = c; end", "fold.bch", 1e-3);
  CHECK_FALSE(run.v.exact);
  CHECK(run.v.headline.find("exactly") == std::string::npos);
  CHECK(run.v.headline.find("for every value of the interval constants") != std::string::npos);
  // No root of any value was discarded: +-sqrt(c) lies in a solution box.
  for (int k = 0; k <= 20; ++k) {
    const double x = std::sqrt(k / 20.0);
    bool plus = false, minus = false;
    for (const Box& s : run.r.subproblems[0].solutions) {
      plus = plus || contains_point(s, {x});
      minus = minus || contains_point(s, {-x});
    }
    CHECK(plus);
    CHECK(minus);
  }
}

TEST_CASE("interval constants: the CLI says so, check re-proves it, bad input writes nothing",
          "[peer][interval-constants][cli]") {
  const std::string bch = test::scratch("thick.bch"), json = test::scratch("thick.json");
  std::ofstream(bch) << "Constants\n  c in [3.9, 4.1];\nVariables\n  x in [0.5, 3];\nConstraints\n  x^2 = c;\nend\n";
  const test::Ran ran = test::run_cli("solve " + bch + " --json " + json);
  REQUIRE(ran.code == 0);
  CHECK(ran.out.find("exactly 1 root in the domain for every value of the interval constants") != std::string::npos);
  CHECK(ran.out.find("model     interval constants [3.9, 4.1]") != std::string::npos);
  const nlohmann::json j = test::read_json(json);
  const auto box = j["roots"][0]["box"][0];
  CHECK(box[0].get<double>() <= std::sqrt(3.9));
  CHECK(box[1].get<double>() >= std::sqrt(4.1));
  CHECK(test::run_cli("check " + json).code == 0);

  const std::string bad = test::scratch("bad-interval.bch"), out = test::scratch("bad-interval.json");
  std::ofstream(bad) << "Constants\n  c in [1, 2];\nVariables\n  x in [0, c];\nConstraints\n  x = 1;\nend\n";
  const test::Ran refused = test::run_cli("solve " + bad + " --json " + out);
  CHECK(refused.code == 2);
  CHECK(refused.out.find(bad + ":4: upper bound of variable 'x'") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(out));
}
