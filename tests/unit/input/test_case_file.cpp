#include "interval/rigorous.hpp"
#include "formulate/load.hpp"
#include "formulate/spherical.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>

using namespace linkbox;
using input::InputError;
using formulate::load_case;
using formulate::load_case_text;

namespace {

const std::string kSource = LINKBOX_SOURCE_DIR;

bool same(const Interval& a, const Interval& b) { return a.lower() == b.lower() && a.upper() == b.upper(); }

model::System polynomial_system(const formulate::LoadedCase& c) {
  REQUIRE(c.formulation);
  REQUIRE(c.formulation->kind() == "polynomial");
  return c.formulation->subproblem(0).system;
}

const input::SphericalCase& spherical_case(const formulate::LoadedCase& c) {
  auto* f = dynamic_cast<const formulate::SphericalFormulation*>(c.formulation.get());
  REQUIRE(f);
  return f->spherical_case();
}

// Every planted root (a point box) makes every equation's enclosure contain 0.
bool satisfies(const model::System& s, const Box& root) {
  for (auto& e : s.equations)
    if (!boost::numeric::zero_in(e.eval(root))) return false;
  return true;
}

struct BadCase {
  const char* file;
  int line;
  const char* message_part;
};

// One entry per file in tests/data/bad; the test below fails when a file has no entry.
const BadCase kBadCases[] = {
    {"toml-syntax.toml", 5, "TOML syntax error"},
    {"invalid-utf8.toml", 2, "TOML syntax error"},
    {"empty.toml", 1, "missing case kind (key 'kind')"},
    {"missing-kind.toml", 1, "missing case kind (key 'kind')"},
    {"kind-not-string.toml", 1, "kind must be a string, found an integer"},
    {"unknown-kind.toml", 2, "unknown kind 'planar' (known: linkage, polynomial, spherical)"},
    {"missing-variables.toml", 1, "missing variables (key 'variables')"},
    {"domain-wrong-type.toml", 4, "domain of variable 'x' must be an array of 2 numbers, found a string"},
    {"domain-wrong-length.toml", 4, "must be an array of 2 numbers, found an array of 3"},
    {"equations-not-array.toml", 4, "equations must be an array, found a string"},
    {"unknown-key.toml", 4, "unknown key 'equation' in a polynomial case"},
    {"unknown-variable.toml", 9, "equation 2 \"x^2 + z - 1\": unknown variable 'z' (column 6)"},
    {"duplicate-variable.toml", 6, "duplicate variable 'x' (first declared on line 4)"},
    {"reserved-variable.toml", 4, "variable name 'pi' is not usable in equations"},
    {"empty-domain.toml", 5, "empty domain of variable 'y': lower bound exceeds upper bound"},
    {"overflow-domain.toml", 4, "\"1e400\": number 1e400 is outside the range of a double"},
    {"no-equations.toml", 4, "no equations"},
    {"equation-parse-error.toml", 9, "equation 2 \"x^2 + * y\": unexpected character '*'"},
    {"constant-equation.toml", 5, "involves no variable"},
    {"function-of-variable.toml", 5, "outside the domain of log on the whole domain"},
    {"duplicate-joint.toml", 6, "duplicate joint 'a' (first declared on line 4)"},
    {"unknown-joint.toml", 8, "unknown joint 'c'"},
    {"zero-axis.toml", 8, "axis of zero length"},
    {"nan-axis.toml", 8, "axis must be finite, found nan"},
    {"infinite-angle.toml", 8, "angle must be finite, found +inf"},
    {"bad-angle-expression.toml", 8,
     "angle: \"pi/(2 - 2)\": division by an interval containing zero (column 3)"},
    {"factor-none.toml", 9,
     "a factor is a joint { joint, axis }, a fixed rotation { axis, angle } or a constant"},
    {"factor-axis-only.toml", 8, "factor has an axis but neither 'joint' nor 'angle'"},
    {"factor-several.toml", 8, "factor mixes 'joint' and 'quaternion'; use exactly one"},
    {"quaternion-length.toml", 8, "quaternion (w, x, y, z) must be an array of 4 numbers, found an array of 3"},
    {"quaternion-zero.toml", 9, "quaternion is zero"},
    {"no-loops.toml", 4, "no loops"},
    {"missing-loops.toml", 1, "missing loops"},
    {"axis-wrong-type.toml", 8, "axis must be a number (integer, float or expression string), found a boolean"},
    {"inverse-wrong-type.toml", 8, "inverse must be true or false, found a string"},
    {"joint-unused.toml", 6, "joint 'c' is used in no loop"},  // from SphericalFormulation
    {"joint-twice-in-loop.toml", 9, "appears twice in loop 'main'"},
    {"duplicate-output.toml", 10, "duplicate output name 'R' (first declared on line 7)"},
    {"empty-loop.toml", 9, "factors of loop 'second': no factors"},
};

}  // namespace

TEST_CASE("case file: every bad input is a InputError with file and line", "[case_file]") {
  for (const BadCase& bad : kBadCases) {
    const std::string path = kSource + "/tests/data/bad/" + bad.file;
    INFO(bad.file);
    try {
      load_case(path);
      FAIL("loaded without error");
    } catch (const InputError& e) {
      INFO(e.what());
      CHECK(e.file == path);
      CHECK(e.line == bad.line);
      CHECK(e.message.find(bad.message_part) != std::string::npos);
      CHECK(std::string(e.what()) == path + ":" + std::to_string(bad.line) + ": " + e.message);
    }
  }
}

TEST_CASE("case file: every bad file has an expectation", "[case_file]") {
  std::set<std::string> listed;
  for (const BadCase& bad : kBadCases) listed.insert(bad.file);
  for (auto& entry : std::filesystem::directory_iterator(kSource + "/tests/data/bad")) {
    INFO(entry.path().filename().string());
    CHECK(listed.count(entry.path().filename().string()) == 1);
  }
}

TEST_CASE("case file: a missing file is reported at line 0", "[case_file]") {
  const std::string path = kSource + "/tests/data/bad/does-not-exist.toml";
  try {
    load_case(path);
    FAIL("loaded a file that does not exist");
  } catch (const InputError& e) {
    CHECK(e.line == 0);
    CHECK(std::string(e.what()) == path + ":0: no such case file");
  }
  CHECK_THROWS_AS(load_case(kSource + "/tests/data/bad"), InputError);  // a directory
}

TEST_CASE("case file: circle-line", "[case_file]") {
  const formulate::LoadedCase c = load_case(kSource + "/cases/polynomial/circle-line.toml");
  CHECK(c.kind == "polynomial");
  CHECK(c.name == "circle-line");
  const model::System s = polynomial_system(c);
  REQUIRE(s.names() == std::vector<std::string>{"x", "y"});
  REQUIRE(s.equations.size() == 2);
  CHECK(same(s.variables[0].domain, Interval(-2.0, 2.0)));
  const Interval r = rigorous::sqrt(Interval(0.5));
  CHECK(satisfies(s, {r, r}));
  CHECK(satisfies(s, {-r, -r}));
  CHECK_FALSE(satisfies(s, {Interval(1.0), Interval(0.0)}));
}

TEST_CASE("case file: planted-cubic has its planted roots", "[case_file]") {
  const model::System s = polynomial_system(load_case(kSource + "/cases/polynomial/planted-cubic.toml"));
  REQUIRE(s.equations.size() == 3);
  CHECK(s.equation_names == std::vector<std::string>{"p1", "p2", "p3"});
  CHECK(s.equations[2].total_degree() == 3);
  double v[] = {-1.0, 0.5, 2.0};
  std::sort(v, v + 3);
  int roots = 0;
  do {
    CHECK(satisfies(s, {Interval(v[0]), Interval(v[1]), Interval(v[2])}));
    ++roots;
  } while (std::next_permutation(v, v + 3));
  CHECK(roots == 6);
  CHECK_FALSE(satisfies(s, {Interval(-1.0), Interval(0.5), Interval(0.5)}));
}

TEST_CASE("case file: numbers are enclosed as the decimals written", "[case_file]") {
  // The domain line has a 2-byte character before the floats: toml++ columns count code points.
  const formulate::LoadedCase c = load_case_text(R"(kind = "polynomial"
name = "numbers"
variables = [
  { name = "x", domain = ["-pi", "pi/2"] },
  { name = "y", domain = [0.0175, 1_000.000_1] },
  { name = "z", domain = [-9007199254740993, 1e-7] }, # é
]
equations = [ { name = "é", equation = "x + y + z" } ]
)",
                                          "numbers.toml");
  const model::System s = polynomial_system(c);
  const Interval pi = rigorous::pi();
  CHECK(s.variables[0].domain.lower() == (-pi).lower());
  CHECK(s.variables[0].domain.upper() == (pi / Interval(2.0)).upper());
  CHECK(s.variables[1].domain.lower() == rigorous::decimal("0.0175").lower());
  CHECK(s.variables[1].domain.upper() == rigorous::decimal("1000.0001").upper());
  CHECK(s.variables[1].domain.lower() < 0.0175);  // the double 0.0175 is above the decimal
  // -(2^53 + 1) is not a double: the integer is enclosed, not rounded.
  CHECK(s.variables[2].domain.lower() == -9007199254740994.0);
  CHECK(s.variables[2].domain.upper() == rigorous::decimal("1e-7").upper());
  CHECK(s.equation_names == std::vector<std::string>{"é"});
}

TEST_CASE("case file: floats after multi-byte characters are still recovered", "[case_file]") {
  const formulate::LoadedCase c = load_case_text(R"(kind = "spherical"
name = "unicode"
joints = ["φ1", "φ2"]
[[loops]]
factors = [ { joint = "φ1", axis = [0, 0.0175, 1] }, { joint = "φ2", axis = [1, 0, 0] } ]
)",
                                          "unicode.toml");
  const input::SphericalCase& sc = spherical_case(c);
  CHECK(same(sc.loops[0].factors[0].axis[1], rigorous::decimal("0.0175")));
  CHECK(sc.loops[0].name == "loop 1");
}

TEST_CASE("case file: spherical wrist", "[case_file]") {
  const std::string text = R"(kind = "spherical"
name = "wrist"
joints = ["phi1", "phi2", "phi3"]
[[loops]]
name = "wrist"
factors = [
  { joint = "phi1", axis = [0, 0, 1] },
  { axis = [1, 0, 0], angle = "pi/2" },
  { joint = "phi2", axis = [0, 0, 2], inverse = true },
  { axis = [1, 0, 0], angle = 0.0175, inverse = true },
  { joint = "phi3", axis = [0, 1, 0] },
  { quaternion = ["0.0196", 0.098, 0.65, -0.74], inverse = true },
]
[[outputs]]
name = "R"
rotation = [ { joint = "phi1", axis = [0, 0, 1] }, { joint = "phi2", axis = [1, 0, 0] } ]
)";
  const formulate::LoadedCase c = load_case_text(text, "wrist.toml");
  CHECK(c.kind == "spherical");
  CHECK(c.name == "wrist");
  CHECK(c.file == "wrist.toml");
  CHECK(c.formulation->kind() == "spherical");
  const input::SphericalCase& sc = spherical_case(c);
  CHECK(sc.name == "wrist");
  CHECK(sc.file == "wrist.toml");
  REQUIRE(sc.joints.size() == 3);
  CHECK(sc.joints[2].name == "phi3");
  CHECK(sc.joints[2].line == 3);
  REQUIRE(sc.loops.size() == 1);
  const input::Loop& loop = sc.loops[0];
  CHECK(loop.name == "wrist");
  CHECK(loop.line == 4);
  REQUIRE(loop.factors.size() == 6);
  using Kind = input::Factor::Kind;

  const input::Factor& f0 = loop.factors[0];
  CHECK(f0.kind == Kind::joint);
  CHECK(f0.joint == 0);
  CHECK(f0.line == 7);
  CHECK(same(f0.axis[2], Interval(1.0)));

  const input::Factor& f1 = loop.factors[1];
  CHECK(f1.kind == Kind::fixed_rotation);
  CHECK(same(f1.angle, rigorous::pi() / Interval(2.0)));

  const input::Factor& f2 = loop.factors[2];  // inverse joint: axis negated
  CHECK(f2.joint == 1);
  CHECK(same(f2.axis[2], Interval(-2.0)));

  const input::Factor& f3 = loop.factors[3];  // inverse fixed rotation: angle negated
  CHECK(same(f3.angle, -rigorous::decimal("0.0175")));

  const input::Factor& f5 = loop.factors[5];  // inverse constant: conjugate
  CHECK(f5.kind == Kind::constant);
  CHECK(f5.line == 12);
  CHECK(same(f5.q[0], rigorous::decimal("0.0196")));
  CHECK(same(f5.q[1], -rigorous::decimal("0.098")));
  CHECK(same(f5.q[3], rigorous::decimal("0.74")));

  REQUIRE(sc.outputs.size() == 1);
  CHECK(sc.outputs[0].name == "R");
  CHECK(sc.outputs[0].line == 14);
  CHECK(sc.outputs[0].factors.size() == 2);
  CHECK(c.formulation->subproblem_count() == 8);

  // Without the source text (a caller that parsed the TOML itself) floats are widened by an
  // ulp each side of toml++'s double, which still contains the decimal.
  const toml::table root = toml::parse(text);
  const input::SphericalCase direct = input::read_spherical(root, "wrist.toml");
  const Interval angle = -direct.loops[0].factors[3].angle;
  CHECK(angle.lower() <= rigorous::decimal("0.0175").lower());
  CHECK(angle.upper() >= rigorous::decimal("0.0175").upper());
  CHECK(direct.loops[0].factors[3].line == 10);
}

TEST_CASE("case file: load_polynomial on a parsed table", "[case_file]") {
  const toml::table root = toml::parse(R"(kind = "polynomial"
name = "p"
variables = [ { name = "x", domain = [0, 1] } ]
equations = [ "x - 0.5" ]
)");
  const model::System s = input::read_polynomial(root, "p.toml");
  REQUIRE(s.equations.size() == 1);
  CHECK(same(s.equations[0].constant_term(), Interval(-0.5)));
  CHECK(s.equation_names == std::vector<std::string>{""});
}

TEST_CASE("case file: a linkage's parameters are told apart as written, not by enclosure", "[case_file]") {
  const input::Case c = input::read_case_text(R"(kind = "linkage"
name = "keys"
ground = "L3"
[[loops]]
links = [
  { joint = "J1", link = "L1", a = 1.50, d = 0, alpha = 1.91 },
  { joint = "J2", link = "L2", a = 15e-1, d = 0.0, alpha = 1.9100000000000001 },
  { joint = "J3", link = "L3", a = "3/2", d = -0.0, alpha = 1_91e-2 },
]
)",
                                              "keys.toml");
  const auto& links = std::get<input::LinkageCase>(c.description).loops.at(0).links;
  using input::same_real;
  CHECK(same_real(links[0].exact.a, links[1].exact.a));   // 1.50 = 15e-1
  CHECK(!same_real(links[0].exact.a, links[2].exact.a));  // an expression is never a decimal
  CHECK(same_real(links[0].exact.d, links[1].exact.d));
  CHECK(same_real(links[0].exact.d, links[2].exact.d));  // -0.0 = 0
  // 1.91 and 1.9100000000000001 have one enclosure, but are not one real.
  CHECK(same(links[0].alpha, links[1].alpha));
  CHECK(!same_real(links[0].exact.alpha, links[1].exact.alpha));
  CHECK(same_real(links[0].exact.alpha, links[2].exact.alpha));
  CHECK(!same_real("", ""));
}
