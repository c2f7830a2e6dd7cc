// Functions of variables (model/lifting.hpp): a system written with sin, cos, tan and sqrt
// (links and divisions: test_links.cpp) must give, in the variables the user declared and one
// to one, the roots that its closed form or its hand-lifted twin gives; what cannot be lifted
// soundly is an InputError naming the line; an unbounded domain gets the default bound, which
// the headline states.
#include "formulate/load.hpp"
#include "tests/solved_case.hpp"
#include "input/expression.hpp"
#include "input/input_error.hpp"
#include "model/lifting.hpp"
#include "report/json.hpp"
#include "solve/solve_case.hpp"
#include "verify/certify_case.hpp"
#include "verify/check.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>

using namespace linkbox;

namespace {

const std::string kSource = LINKBOX_SOURCE_DIR;

using Run = test::SolvedCase;
using test::solve_loaded;
using test::solve_text;

Run solve_file(const std::string& path, const std::string& prune = "auto", double sigma = 1e-4) {
  return solve_loaded(formulate::load_case(kSource + "/" + path), prune, sigma);
}

std::string polynomial_case(const std::string& variables, const std::string& equations) {
  return "kind = \"polynomial\"\nname = \"t\"\nvariables = [ " + variables + " ]\nequations = [ " + equations + " ]\n";
}

const model::System& system_of(const Run& run) {
  static thread_local formulate::SubProblem sub;
  sub = run.c.formulation->subproblem(0);
  return sub.system;
}

// Whether some root's midpoint is within `tol` of `point` in every coordinate.
bool has_root_near(const std::vector<Box>& roots, const std::vector<double>& point, double tol = 1e-10) {
  for (auto& r : roots) {
    bool near = true;
    for (size_t i = 0; i < point.size(); ++i) near = near && std::fabs(median(r[i]) - point[i]) <= tol;
    if (near) return true;
  }
  return false;
}

std::string load_error(const std::string& toml, int* line = nullptr) {
  try {
    formulate::load_case_text(toml, "inline.toml");
  } catch (const input::InputError& e) {
    if (line) *line = e.line;
    return e.message;
  }
  return "";
}

}  // namespace

TEST_CASE("a system in angles gives the certified roots of its hand-lifted twin", "[functions]") {
  const Run angles = solve_file("cases/polynomial/kin-angles.toml", "hc4,newton", 1e-6);
  const Run twin = solve_text(polynomial_case(
      R"~({ name = "c1", domain = [-1, 1] }, { name = "s1", domain = [-1, 1] },
         { name = "c2", domain = [-1, 1] }, { name = "s2", domain = [-1, 1] })~",
      R"~("c1 + 0.8*(c1*c2 - s1*s2) - 1.2", "s1 + 0.8*(s1*c2 + c1*s2) - 0.5", "c1^2 + s1^2 - 1", "c2^2 + s2^2 - 1")~"));
  REQUIRE(angles.v.exact);
  REQUIRE(twin.v.exact);
  CHECK(verify::check_certificates(angles.j, *angles.c.formulation).failures.empty());
  REQUIRE(angles.roots.size() == 2);
  REQUIRE(twin.roots.size() == 2);
  CHECK(angles.c.formulation->output_names() == std::vector<std::string>{"t1", "t2"});
  // One to one: each angle root's cos and sin lie in exactly one twin root (to its width).
  std::vector<int> matched(2, 0);
  for (auto& a : angles.roots) {
    const double t1 = median(a[0]), t2 = median(a[1]);
    const std::vector<double> cs{std::cos(t1), std::sin(t1), std::cos(t2), std::sin(t2)};
    for (size_t k = 0; k < 2; ++k) matched[k] += has_root_near({twin.roots[k]}, cs, 1e-12);
  }
  CHECK(matched == std::vector<int>{1, 1});
  // The closed form (law of cosines, see the case file).
  const double t2 = std::acos(1.0 / 32), t1 = std::atan2(0.5, 1.2) - std::atan2(0.8 * std::sin(t2), 1 + 0.8 * std::cos(t2));
  CHECK(has_root_near(angles.roots, {t1, t2}, 1e-12));
  const double t1b = std::atan2(0.5, 1.2) + std::atan2(0.8 * std::sin(t2), 1 + 0.8 * std::cos(t2));
  CHECK(has_root_near(angles.roots, {t1b, -t2}, 1e-12));
  // What the model print says.
  const auto notes = angles.c.formulation->model_notes();
  REQUIRE(notes.size() == 3);
  CHECK(notes[0] == "lifted: 2 declared variables -> 4 unknowns, 4 equations");
  CHECK(notes[1].find("t1 -> cos(t1), sin(t1) on the unit circle") != std::string::npos);
}

TEST_CASE("kin1 in joint angles: the 16 roots of the lifted kin1, one to one", "[functions][benchmark]") {
  const Run angles = solve_file("cases/benchmarks/kin1-angles.toml");
  std::ifstream in(kSource + "/cases/benchmarks/kin1.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string lifted = text.str();
  for (size_t at; (at = lifted.find("-1e8, 1e8")) != std::string::npos;) lifted.replace(at, 9, "-1, 1");
  const Run twin = solve_loaded(formulate::load_case_text(lifted, "kin1-unit.toml"), "auto", 1e-4);
  REQUIRE(angles.v.exact);
  REQUIRE(twin.v.exact);
  REQUIRE(angles.roots.size() == 16);
  REQUIRE(twin.roots.size() == 16);
  CHECK(verify::check_certificates(angles.j, *angles.c.formulation).failures.empty());
  // kin1.toml orders its unknowns s1, c1, s2, c2, ...
  std::vector<int> hits(16, 0);
  for (auto& a : angles.roots) {
    std::vector<double> sc;
    for (int i = 0; i < 6; ++i) sc.insert(sc.end(), {std::sin(median(a[i])), std::cos(median(a[i]))});
    for (size_t k = 0; k < 16; ++k) hits[k] += has_root_near({twin.roots[k]}, sc, 1e-9);
  }
  CHECK(hits == std::vector<int>(16, 1));
}

TEST_CASE("only what is used is modelled: cos alone, sin alone, tan alone, or the circle", "[functions]") {
  // cos(a) on [0, 3] (within [0, pi]): c alone, a = acos(c).
  Run cos_only = solve_text(polynomial_case(R"~({ name = "a", domain = [0, 3] })~", R"~("cos(a) - 0.25")~"));
  const auto& s1 = system_of(cos_only);
  REQUIRE(s1.lifting);
  CHECK(s1.variables.size() == 1);
  CHECK(s1.equations.size() == 1);
  CHECK(s1.lifting->angles.at(0).chart == model::Lifting::Chart::cos_only);
  REQUIRE(cos_only.roots.size() == 1);
  CHECK(cos_only.v.exact);
  CHECK(std::fabs(median(cos_only.roots[0][0]) - std::acos(0.25)) < 1e-14);

  // sin(2b) on b in [-0.7, 0.7] (2b within [-pi/2, pi/2]): s alone, unit 2.
  Run sin_only = solve_text(polynomial_case(R"~({ name = "b", domain = [-0.7, 0.7] })~", R"~("sin(2*b) = 0.5")~"));
  CHECK(system_of(sin_only).lifting->angles.at(0).chart == model::Lifting::Chart::sin_only);
  CHECK(system_of(sin_only).variables[0].name == "sin(2*b)");
  REQUIRE(sin_only.roots.size() == 1);
  CHECK(std::fabs(median(sin_only.roots[0][0]) - M_PI / 12) < 1e-14);

  // tan(c) its only use: tan(c) itself is the unknown.
  Run tan_only = solve_text(polynomial_case(R"~({ name = "c", domain = [-1.5, 1.5] })~", R"~("tan(c) - 2")~"));
  CHECK(system_of(tan_only).lifting->angles.at(0).chart == model::Lifting::Chart::tan_only);
  REQUIRE(tan_only.roots.size() == 1);
  CHECK(std::fabs(median(tan_only.roots[0][0]) - std::atan(2.0)) < 1e-14);

  // cos(a) on [-1.5, 3]: cos is not one to one there, so sin(a) is modelled too and both
  // roots +-acos(0.25) are found.
  Run circle = solve_text(polynomial_case(R"~({ name = "a", domain = [-1.5, 3] })~", R"~("cos(a) - 0.25")~"));
  CHECK(system_of(circle).lifting->angles.at(0).chart == model::Lifting::Chart::circle);
  CHECK(system_of(circle).equations.size() == 2);  // with c^2 + s^2 = 1
  CHECK(circle.v.exact);
  REQUIRE(circle.roots.size() == 2);
  CHECK(has_root_near(circle.roots, {std::acos(0.25)}, 1e-13));
  CHECK(has_root_near(circle.roots, {-std::acos(0.25)}, 1e-13));
}

TEST_CASE("sin and cos of a multiple angle that is multiplied are unknowns of their own", "[functions]") {
  // r cos(2t) = 1.5, r sin(2t) = 2, q = sin(t) on t in [0, 3]: (r, 2t) is (2.5, a) or
  // (-2.5, a + pi), a = atan2(2, 1.5), so t is a/2 or a/2 + pi/2 (sin(t) makes t the angle).
  Run run = solve_text(polynomial_case(
      R"~({ name = "r", domain = [-10, 10] }, { name = "t", domain = [0, 3] }, { name = "q", domain = [-1, 1] })~",
      R"~("r*cos(2*t) = 1.5", "r*sin(2*t) = 2", "q = sin(t)")~"));
  const auto& s = system_of(run);
  REQUIRE(s.lifting);
  // r, cos t, sin t, q, cos(2t), sin(2t): the products r cos(2t) stay bilinear.
  REQUIRE(s.variables.size() == 6);
  CHECK(s.variables[4].name == "cos(2*t)");
  CHECK(s.variables[5].name == "sin(2*t)");
  CHECK(s.equations.size() == 6);  // three typed, the circle, two definitions
  CHECK(run.v.exact);
  CHECK(verify::check_certificates(run.j, *run.c.formulation).failures.empty());
  REQUIRE(run.roots.size() == 2);
  const double a = std::atan2(2.0, 1.5);
  CHECK(has_root_near(run.roots, {2.5, a / 2, std::sin(a / 2)}, 1e-12));
  CHECK(has_root_near(run.roots, {-2.5, a / 2 + M_PI / 2, std::sin(a / 2 + M_PI / 2)}, 1e-12));
  // Not multiplied: cos(2t) stays its expansion (no unknown is added for it).
  Run alone = solve_text(polynomial_case(R"~({ name = "t", domain = ["-pi", "pi"] })~", R"~("cos(2*t) + sin(t) = 1")~"));
  CHECK(system_of(alone).variables.size() == 2);
}

TEST_CASE("an angle domain of less than a turn counts only roots on its arc", "[functions]") {
  // sin(t) = sin(5.2) has roots 5.2 and 3 pi - 5.2 = 4.2248 in [0, 2 pi]. On [1, 5] the
  // box of (cos t, sin t), [-1, cos 1] x [-1, 1], still holds the point of angle 5.2
  // (cos 5.2 = 0.4685 < cos 1): the arc inequality excludes it.
  Run arc = solve_text(polynomial_case(R"~({ name = "t", domain = [1, 5] })~", R"~("sin(t) - sin(5.2)")~"));
  const auto& s = system_of(arc);
  REQUIRE(s.inequalities.size() == 1);
  CHECK(s.inequalities[0].name == "domain of t");
  CHECK(contains(s.variables[0].domain, std::cos(5.2)));  // the spurious point is in the box
  CHECK(contains(s.variables[1].domain, std::sin(5.2)));
  CHECK(arc.v.exact);
  CHECK(verify::check_certificates(arc.j, *arc.c.formulation).failures.empty());
  REQUIRE(arc.roots.size() == 1);
  CHECK(std::fabs(median(arc.roots[0][0]) - (3 * M_PI - 5.2)) < 1e-13);
  // On [1, 5.25] both count.
  Run wider = solve_text(polynomial_case(R"~({ name = "t", domain = [1, 5.25] })~", R"~("sin(t) - sin(5.2)")~"));
  CHECK(wider.v.exact);
  REQUIRE(wider.roots.size() == 2);
  CHECK(has_root_near(wider.roots, {5.2}, 1e-13));
  CHECK(has_root_near(wider.roots, {3 * M_PI - 5.2}, 1e-13));
  // Within one quadrant the box is the arc: no inequality is needed.
  Run quadrant = solve_text(polynomial_case(R"~({ name = "t", domain = [0.1, 1.5] })~", R"~("sin(t) + cos(t) = 1.3")~"));
  CHECK(system_of(quadrant).inequalities.empty());
  CHECK(quadrant.v.exact);
  // sin t + cos t = sqrt(2) sin(t + pi/4) = 1.3: t = asin(1.3 / sqrt 2) - pi/4 and its mirror.
  REQUIRE(quadrant.roots.size() == 2);
  CHECK(has_root_near(quadrant.roots, {std::asin(1.3 / std::sqrt(2.0)) - M_PI / 4}, 1e-13));
  CHECK(has_root_near(quadrant.roots, {M_PI - std::asin(1.3 / std::sqrt(2.0)) - M_PI / 4}, 1e-13));
}

TEST_CASE("a full turn: the root on the seam is one root", "[functions]") {
  // sin(t) = 0 on [-pi, pi]: t = 0 and t = pi = -pi (one root of the circle).
  Run seam = solve_text(polynomial_case(R"~({ name = "t", domain = ["-pi", "pi"] })~", R"~("sin(t)")~"));
  CHECK(seam.v.exact);
  CHECK(verify::check_certificates(seam.j, *seam.c.formulation).failures.empty());
  REQUIRE(seam.roots.size() == 2);
  CHECK(has_root_near(seam.roots, {0.0}, 1e-14));
  int at_pi = 0;
  for (auto& r : seam.roots) at_pi += std::fabs(std::fabs(median(r[0])) - M_PI) < 1e-12;
  CHECK(at_pi == 1);
  // On [0, 2 pi] the seam is at 0 = 2 pi.
  Run turn = solve_text(polynomial_case(R"~({ name = "t", domain = [0, "2*pi"] })~", R"~("sin(t)")~"));
  CHECK(turn.v.exact);
  REQUIRE(turn.roots.size() == 2);
  CHECK(has_root_near(turn.roots, {M_PI}, 1e-12));
  // cos(2t) + sin(t) = 1: sin t (1 - 2 sin t) = 0, so t in {0, pi, pi/6, 5 pi/6}.
  Run four = solve_text(polynomial_case(R"~({ name = "t", domain = ["-pi", "pi"] })~", R"~("cos(2*t) + sin(t) = 1")~"));
  CHECK(four.v.exact);
  REQUIRE(four.roots.size() == 4);
  CHECK(has_root_near(four.roots, {M_PI / 6}, 1e-12));
  CHECK(has_root_near(four.roots, {5 * M_PI / 6}, 1e-12));
  // An offset: cos(t + pi/3) = 0 at t = pi/6 and t = -5 pi/6.
  Run offset = solve_text(polynomial_case(R"~({ name = "t", domain = ["-pi", "pi"] })~", R"~("cos(t + pi/3)")~"));
  CHECK(offset.v.exact);
  REQUIRE(offset.roots.size() == 2);
  CHECK(has_root_near(offset.roots, {M_PI / 6}, 1e-12));
  CHECK(has_root_near(offset.roots, {-5 * M_PI / 6}, 1e-12));
}

TEST_CASE("tan of an angle also used in sin, and sqrt, are auxiliary unknowns", "[functions]") {
  // sin(t) = 1/2 on [-1, 1]: t = pi/6, x = tan(pi/6) = 1/sqrt(3).
  Run tan = solve_text(polynomial_case(R"~({ name = "t", domain = [-1, 1] }, { name = "x", domain = [-5, 5] })~",
                                       R"~("tan(t) - x", "sin(t) - 0.5")~"));
  CHECK(tan.v.exact);
  REQUIRE(tan.roots.size() == 1);
  CHECK(has_root_near(tan.roots, {M_PI / 6, 1 / std::sqrt(3.0)}, 1e-13));
  CHECK(verify::check_certificates(tan.j, *tan.c.formulation).failures.empty());

  // sqrt(x + 1) + sqrt(x) = 3/2: sqrt(x) = (9/4 - 1) / 3 = 5/12. x^(1/2) is sqrt(x).
  Run sqrt = solve_text(polynomial_case(R"~({ name = "x", domain = [0, 3] })~", R"~("sqrt(x + 1) + x^(1/2) = 1.5")~"));
  const auto& s = system_of(sqrt);
  REQUIRE(s.lifting);
  CHECK(s.lifting->applications.size() == 2);  // sqrt(x) written twice ways is one unknown
  CHECK(s.variables.size() == 3);
  CHECK(s.variables[2].domain.lower() == 0);  // r >= 0
  CHECK(sqrt.v.exact);
  REQUIRE(sqrt.roots.size() == 1);
  CHECK(std::fabs(median(sqrt.roots[0][0]) - 25.0 / 144) < 1e-14);

  // x^(3/2) = 8 at x = 4; sqrt(x^2 + 1) = 2 at x = +-sqrt(3).
  Run power = solve_text(polynomial_case(R"~({ name = "x", domain = [0, 10] })~", R"~("x^(3/2) - 8")~"));
  REQUIRE(power.roots.size() == 1);
  CHECK(std::fabs(median(power.roots[0][0]) - 4) < 1e-13);
  Run both = solve_text(polynomial_case(R"~({ name = "x", domain = [-3, 3] })~", R"~("sqrt(x^2 + 1) = 2")~"));
  CHECK(both.v.exact);
  REQUIRE(both.roots.size() == 2);
  CHECK(has_root_near(both.roots, {std::sqrt(3.0)}, 1e-13));
  CHECK(has_root_near(both.roots, {-std::sqrt(3.0)}, 1e-13));
}

TEST_CASE("abs, min, max, sign and negative powers: the closed forms' roots, certified", "[functions]") {
  // |x - 1| = 1/2: x = 1/2 and 3/2 (|A| is sqrt(A^2), an unknown r >= 0 with r^2 = A^2).
  Run abs = solve_text(polynomial_case(R"~({ name = "x", domain = [-3, 3] })~", R"~("abs(x - 1) - 0.5")~"));
  CHECK(abs.v.exact);
  REQUIRE(abs.roots.size() == 2);
  CHECK(has_root_near(abs.roots, {0.5}, 1e-13));
  CHECK(has_root_near(abs.roots, {1.5}, 1e-13));
  CHECK(system_of(abs).variables.at(1).domain.lower() == 0);

  // min = 1/5 and max = 7/10: (1/5, 7/10) and (7/10, 1/5), and nothing where x = y.
  Run minmax = solve_text(polynomial_case(R"~({ name = "x", domain = [0, 1] }, { name = "y", domain = [0, 1] })~",
                                          R"~("min(x, y) - 0.2", "max(x, y) - 0.7")~"));
  CHECK(minmax.v.exact);
  REQUIRE(minmax.roots.size() == 2);
  CHECK(has_root_near(minmax.roots, {0.2, 0.7}, 1e-13));
  CHECK(has_root_near(minmax.roots, {0.7, 0.2}, 1e-13));

  // sign(x) = y on the circle x^2 + y^2 = 2: (1, 1) and (-1, -1). Where x keeps its sign on
  // the domain, 1/|x| is an unknown; where x may be 0, |x| is cleared and x = 0 is kept out by
  // a strict inequality: a point of the cleared system there is never a certified root.
  Run away = solve_text(polynomial_case(R"~({ name = "x", domain = [0.5, 2] }, { name = "y", domain = [-2, 2] })~",
                                        R"~("sign(x) - y", "x^2 + y^2 - 2")~"));
  CHECK(away.v.exact);
  REQUIRE(away.roots.size() == 1);
  CHECK(has_root_near(away.roots, {1, 1}, 1e-13));
  Run across = solve_text(polynomial_case(R"~({ name = "x", domain = [-2, 2] }, { name = "y", domain = [-2, 2] })~",
                                          R"~("sign(x) - y", "x^2 + y^2 - 2")~"));
  REQUIRE(across.roots.size() == 2);
  CHECK(has_root_near(across.roots, {1, 1}, 1e-13));
  CHECK(has_root_near(across.roots, {-1, -1}, 1e-13));
  for (const Box& r : across.roots) CHECK(!boost::numeric::zero_in(r[0]));

  // x^-2 = 4 at x = 1/2; (x + 1)^(-3/2) = 1/8 at x = 3; both through 1/(the power).
  Run inverse = solve_text(polynomial_case(R"~({ name = "x", domain = [0.1, 3] })~", R"~("x^(-2) - 4")~"));
  CHECK(inverse.v.exact);
  REQUIRE(inverse.roots.size() == 1);
  CHECK(std::fabs(median(inverse.roots[0][0]) - 0.5) < 1e-13);
  Run half = solve_text(polynomial_case(R"~({ name = "x", domain = [0, 10] })~", R"~("(x + 1)^(-3/2) - 0.125")~"));
  CHECK(half.v.exact);
  REQUIRE(half.roots.size() == 1);
  CHECK(std::fabs(median(half.roots[0][0]) - 3) < 1e-12);
  CHECK(verify::check_certificates(half.j, *half.c.formulation).failures.empty());

  // Constants fold: abs(-2) + max(1, 3) + sign(-5) + 2^-1 = 2 + 3 - 1 + 1/2.
  Run folded = solve_text(polynomial_case(R"~({ name = "x", domain = [0, 10] })~",
                                          R"~("x - abs(-2) - max(1, 3) - sign(-5) - 2^-1")~"));
  REQUIRE(folded.roots.size() == 1);
  CHECK(std::fabs(median(folded.roots[0][0]) - 4.5) < 1e-13);
}

TEST_CASE("atan2: the closed forms' roots, certified, and none twice across its cut", "[functions]") {
  const std::string plane = R"~({ name = "x", domain = [-2, 2] }, { name = "y", domain = [-2, 2] })~";
  // On the unit circle atan2(y, x) = 2 at (cos 2, sin 2); its square is 4 at angle -2 too.
  // The domain crosses the cut, so -pi < t <= pi is part of the model.
  Run one = solve_text(polynomial_case(plane, R"~("x^2 + y^2 - 1", "atan2(y, x) - 2")~"));
  CHECK(one.v.exact);
  REQUIRE(one.roots.size() == 1);
  CHECK(has_root_near(one.roots, {std::cos(2.0), std::sin(2.0)}, 1e-13));
  const auto& notes = system_of(one).lifting->notes;
  CHECK(std::any_of(notes.begin(), notes.end(), [](auto& n) { return n.find("cross the cut") != std::string::npos; }));
  Run both = solve_text(polynomial_case(plane, R"~("x^2 + y^2 - 1", "atan2(y, x)^2 - 4")~"));
  CHECK(both.v.exact);
  REQUIRE(both.roots.size() == 2);
  CHECK(has_root_near(both.roots, {std::cos(2.0), -std::sin(2.0)}, 1e-13));
  // Away from the cut (y < 0 on the whole domain) no inequality on t is needed.
  Run lower = solve_text(polynomial_case(R"~({ name = "x", domain = [-2, 2] }, { name = "y", domain = [-2, -0.1] })~",
                                         R"~("x^2 + y^2 - 1", "atan2(y, x) + 2.5")~"));
  CHECK(lower.v.exact);
  REQUIRE(lower.roots.size() == 1);
  CHECK(has_root_near(lower.roots, {std::cos(2.5), -std::sin(2.5)}, 1e-13));
  CHECK(system_of(lower).inequalities.size() == 1);
  // Just above and just below the cut: atan2(+-1e-9, x) = +-c x^2 has one root near x = -1
  // (angle near +-pi) and one near x = 0.00068, each once.
  for (const double y : {1e-9, -1e-9}) {
    INFO("y = " << y);
    const std::string sign = y > 0 ? "" : "-";
    Run near = solve_text(polynomial_case(plane, "\"y - " + sign + "1e-9\", \"atan2(y, x) - " + sign +
                                                     "3.14159265358979*x^2\""));
    CHECK(near.v.exact);
    REQUIRE(near.roots.size() == 2);
    for (const Box& r : near.roots) {
      const double x = median(r[0]);
      CHECK(std::fabs(std::atan2(y, x) - (y > 0 ? 1 : -1) * 3.14159265358979 * x * x) < 1e-9);
    }
  }
  // On the cut itself (y = 0, x = -1, angle pi) the root is on the boundary of t <= pi: it is
  // unresolved, never certified (and never twice), and its box holds it.
  Run cut = solve_text(polynomial_case(plane, R"~("y", "atan2(y, x) - 3.14159265358979*x^2")~"));
  CHECK(cut.roots.empty());
  bool held = false;
  for (auto& s : cut.r.subproblems)
    for (auto& b : s.solutions) {
      const Box out = cut.c.formulation->to_output(s.index, b);
      held = held || (contains(out[0], -std::sqrt(M_PI / 3.14159265358979)) && contains(out[1], 0.0));
    }
  CHECK(held);
}

TEST_CASE("asinh, acosh and atanh: the closed forms' roots, certified, and constants folded", "[functions]") {
  Run asinh = solve_text(polynomial_case(R"~({ name = "x", domain = [-3, 3] })~", R"~("asinh(2*x) - 1")~"));
  CHECK(asinh.v.exact);
  REQUIRE(asinh.roots.size() == 1);
  CHECK(has_root_near(asinh.roots, {std::sinh(1.0) / 2}, 1e-13));
  // acosh is defined from 1: a domain reaching below loses no root. atanh is defined inside
  // (-1, 1), where it is unbounded toward the ends: a domain reaching them is refused (below).
  Run acosh = solve_text(polynomial_case(R"~({ name = "x", domain = [0, 5] })~", R"~("acosh(x) - 2")~"));
  CHECK(acosh.v.exact);
  REQUIRE(acosh.roots.size() == 1);
  CHECK(has_root_near(acosh.roots, {std::cosh(2.0)}, 1e-12));
  Run atanh = solve_text(polynomial_case(R"~({ name = "x", domain = [-0.9, 0.95] })~", R"~("atanh(x) - 0.5")~"));
  CHECK(atanh.v.exact);
  REQUIRE(atanh.roots.size() == 1);
  CHECK(has_root_near(atanh.roots, {std::tanh(0.5)}, 1e-13));
  Run folded = solve_text(polynomial_case(R"~({ name = "x", domain = [0, 10] })~",
                                          R"~("x - asinh(1) - acosh(2) - atanh(0.5) - atan2(1, -1)")~"));
  REQUIRE(folded.roots.size() == 1);
  CHECK(std::fabs(median(folded.roots[0][0]) - (std::asinh(1.0) + std::acosh(2.0) + std::atanh(0.5) + 0.75 * M_PI)) <
        1e-13);
}

TEST_CASE("the back-map encloses the angle: random points of the lifted circle", "[functions]") {
  // For every chart, to_declared of a tiny box around (cos u, sin u) must contain t = u/unit,
  // and to_lifted of t must contain the lifted point.
  const char* cases[] = {
      R"~({ name = "t", domain = ["-pi", "pi"] })~", R"~("sin(t) + cos(t)")~",  // circle, full turn
      R"~({ name = "t", domain = [0.3, 5.5] })~", R"~("sin(t) + cos(t)")~",     // circle, arc
      R"~({ name = "t", domain = [-6, -3.5] })~", R"~("cos(t) - 0.5")~",        // cos only, branch -2
      R"~({ name = "t", domain = [2, 4] })~", R"~("sin(t)")~",                  // sin only, branch 1
      R"~({ name = "t", domain = [2, 4] })~", R"~("tan(t)")~",                  // tan only, branch 1
      R"~({ name = "t", domain = [-1, 2] })~", R"~("cos(3*t) + sin(2*t)")~",    // circle, multiples
      R"~({ name = "t", domain = [0, 4] })~", R"~("cos(t/2) - 0.3")~",          // unit 1/2
  };
  for (size_t k = 0; k < std::size(cases); k += 2) {
    INFO(cases[k + 1]);
    const auto loaded = formulate::load_case_text(polynomial_case(cases[k], cases[k + 1]), "inline.toml");
    const auto sub = loaded.formulation->subproblem(0);
    const auto& lifting = *sub.system.lifting;
    const Interval domain = lifting.declared[0].domain;
    for (int i = 0; i <= 100; ++i) {
      const double t = domain.lower() + (domain.upper() - domain.lower()) * i / 100.0;
      const Box lifted = loaded.formulation->output_to_natural(0, Box{Interval(t)});
      Box around = lifted;
      for (auto& x : around) x = x + Interval(-1e-13, 1e-13);
      const Box back = loaded.formulation->natural_to_output(0, around);
      // A full turn may report the seam at the other end: t modulo one turn there.
      const double period = 2 * M_PI / median(lifting.angles[0].unit);
      bool in = contains(back[0], t);
      for (int k = -1; lifting.angles[0].full_turn && k <= 1; k += 2) in = in || contains(back[0], t + k * period);
      CHECK(in);
      CHECK(width(back[0]) < 1e-6);
    }
  }
}

TEST_CASE("functions of variables: what cannot be lifted is an InputError at its line", "[functions][input]") {
  struct Bad {
    std::string variables, equations;
    int line;
    std::string part;
  };
  const Bad bad[] = {
      {R"~({ name = "t", domain = [0, 2] })~", R"~("tan(t) + t")~", 6, "meets a pole of tan"},
      {R"~({ name = "t", domain = [0, 7] })~", R"~("sin(t)")~", 4, "spans more than a full turn"},
      {R"~({ name = "t", domain = [0, 2] })~", R"~("tan(t) - 1")~", 6, "meets a pole of tan"},
      {R"~({ name = "x", domain = [0, 1] })~", R"~("sqrt(x - 5) - 1")~", 6, "negative on the whole domain"},
      {R"~({ name = "x", domain = [0, 1] })~", R"~("log(x - 5) - 2")~", 6, "outside the domain of log on the whole"},
      {R"~({ name = "x", domain = [0, 1] })~", R"~("log(x) - 2")~", 6, "its value is not bounded on the domain"},
      {R"~({ name = "x", domain = [-1, 1] })~", R"~("sqrt(1/x) - 2")~", 6, "has a divisor that may be 0"},
      {R"~({ name = "t", domain = [0, 1] })~", R"~("sin(t) + sin(pi*t)")~", 6, "integer multiples of one unit"},
      {R"~({ name = "t", domain = [0, 1] })~", R"~("cos(2*t) - 2*cos(t)^2 + 1")~", 6, "constant once sin and cos"},
      {R"~({ name = "x", domain = [0, 1] })~", R"~("x^(1/3) - 1")~", 6, "an integer or half-integer"},
      {R"~({ name = "x", domain = [0, 1] })~", R"~("x <= 1")~", 6, "inequalities go under 'inequalities'"},
      {R"~({ name = "x", domain = [0, 1] })~", R"~("x - atan2(0, 0)")~", 6, "atan2(0, 0) is not defined"},
      {R"~({ name = "x", domain = [0, 1] })~", R"~("acosh(x - 2) - 1")~", 6, "outside the domain of acosh"},
      {R"~({ name = "x", domain = [-2, 2] })~", R"~("atanh(x) - 1")~", 6, "its value is not bounded on the domain"},
  };
  for (auto& b : bad) {
    std::string toml = "kind = \"polynomial\"\nname = \"t\"\nvariables = [\n  " + b.variables + "\n]\nequations = [ " +
                       b.equations + " ]\n";
    INFO(toml);
    int line = -1;
    const std::string message = load_error(toml, &line);
    CHECK(message.find(b.part) != std::string::npos);
    CHECK(line == b.line);
  }
}

TEST_CASE("an unbounded domain is searched within the default bound, and the headline says so",
          "[functions][input]") {
  // x^2 = 4 with x in [-inf, inf]: both roots; with x in [-5e3, "inf"], one; x - 2e8 = 0 has
  // its root beyond the bound, so none is claimed there, and the headline says within what.
  Run both = solve_text(polynomial_case(R"~({ name = "x", domain = [-inf, inf] })~", R"~("x^2 - 4")~"));
  CHECK(both.roots.size() == 2);
  CHECK(both.v.exact);
  CHECK(both.v.headline.find("(with x in [-1e8, 1e8], a default bound)") != std::string::npos);
  Run half = solve_text(polynomial_case(R"~({ name = "x", domain = [0, "inf"] })~", R"~("x^2 - 4")~"));
  CHECK(half.roots.size() == 1);
  CHECK(half.v.headline.find("(with x in [0, 1e8], a default bound)") != std::string::npos);
  Run beyond = solve_text(polynomial_case(R"~({ name = "x", domain = [-inf, inf] })~", R"~("x - 2e8")~"));
  CHECK(beyond.roots.empty());
  CHECK(beyond.v.headline.find("exactly 0 roots in the domain (with x in [-1e8, 1e8]") == 0);
  // A finite domain is unchanged and says nothing of a bound.
  Run finite = solve_text(polynomial_case(R"~({ name = "x", domain = [-3, 3] })~", R"~("x^2 - 4")~"));
  CHECK(finite.v.headline.find("default bound") == std::string::npos);
}

TEST_CASE("parse_with_functions keeps each distinct application once", "[functions][expression]") {
  std::vector<model::Application> apps;
  const std::vector<std::string> vars{"t", "x"};
  const model::Polynomial p = input::parse_with_functions("sin(t) + sin( t ) * cos(2*t + 1) + sqrt(x) - x^(1/2)", vars, apps);
  REQUIRE(apps.size() == 3);
  CHECK(apps[0].function == model::Application::Function::sin);
  CHECK(apps[0].text == "sin(t)");
  CHECK(apps[1].text == "cos(2*t + 1)");
  CHECK(apps[2].function == model::Application::Function::sqrt);
  // sqrt(x) - x^(1/2) cancels; sin(t) is variable 2, cos(...) variable 3.
  CHECK(p.variables() == std::vector<int>{2, 3});
  // Without the application list the old rule holds.
  CHECK_THROWS_AS(input::parse_polynomial("sin(t)", vars), input::ParseError);
  // Constant arguments fold as before, also where a variable cancels.
  apps.clear();
  const model::Polynomial q = input::parse_with_functions("sin(x - x) + 2^(1/2)", vars, apps);
  CHECK(apps.empty());
  CHECK(contains(q.constant_term(), std::sqrt(2.0)));
}
