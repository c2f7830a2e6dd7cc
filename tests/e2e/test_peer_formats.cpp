// The peers' formats: Minibex (.bch) and CuikSuite (.cuik) files read as polynomial cases, the
// converter to TOML, and the CLI on them. A peer's file must mean what it means to the peer
// (precedence, indices from 1, decimals as written) or be refused at its line.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "tests/cli_run.hpp"
#include "input/case_file.hpp"
#include "input/peer_case.hpp"
#include "input/to_toml.hpp"
#include "interval/rigorous.hpp"

using namespace linkbox;
using input::InputError;

namespace {

const std::string kSource = LINKBOX_SOURCE_DIR;

bool same(const Interval& a, const Interval& b) { return a.lower() == b.lower() && a.upper() == b.upper(); }

const model::System& system_of(const input::Case& c) {
  REQUIRE(c.kind == "polynomial");
  REQUIRE(std::holds_alternative<model::System>(c.description));
  return std::get<model::System>(c.description);
}

// Same domains and the same polynomials, coefficient for coefficient (variables by position).
void require_same_system(const model::System& a, const model::System& b, bool same_names = true) {
  REQUIRE(a.variables.size() == b.variables.size());
  for (size_t i = 0; i < a.variables.size(); ++i) {
    INFO("variable " << a.variables[i].name);
    if (same_names) CHECK(a.variables[i].name == b.variables[i].name);
    CHECK(same(a.variables[i].domain, b.variables[i].domain));
  }
  REQUIRE(a.equations.size() == b.equations.size());
  for (size_t i = 0; i < a.equations.size(); ++i) {
    const auto& ta = a.equations[i].terms();
    const auto& tb = b.equations[i].terms();
    INFO("equation " << i + 1 << ": " << a.equations[i].to_string(a.names()) << "  vs  "
                     << b.equations[i].to_string(b.names()));
    REQUIRE(ta.size() == tb.size());
    for (auto ia = ta.begin(), ib = tb.begin(); ia != ta.end(); ++ia, ++ib) {
      CHECK(ia->first == ib->first);
      CHECK(same(ia->second, ib->second));
    }
  }
}

model::System read_text(const std::string& text, const std::string& file) {
  return system_of(input::read_case_text(text, file));
}

Interval coefficient(const model::Polynomial& p, const model::Powers& powers) {
  auto it = p.terms().find(powers);
  return it == p.terms().end() ? Interval(0.0) : it->second;
}

}  // namespace

TEST_CASE("peer formats: the bundled .bch and .cuik files are their TOML twins", "[peer]") {
  struct Pair {
    const char* peer;
    const char* toml;
    bool same_names;
  };
  const Pair pairs[] = {
      {"eco9.bch", "eco9.toml", false},  // a vector: x_1 .. x_8 for x1 .. x8
      {"caprasse.bch", "caprasse.toml", true},
      {"kin1.bch", "kin1.toml", true},
      {"cyclohexan3d.cuik", "cyclohexan3d.toml", true},
  };
  for (const Pair& p : pairs) {
    INFO(p.peer);
    const input::Case peer = input::read_case(kSource + "/cases/benchmarks/" + p.peer);
    const input::Case twin = input::read_case(kSource + "/cases/benchmarks/" + p.toml);
    CHECK(peer.name == twin.name);
    CHECK(peer.file == kSource + "/cases/benchmarks/" + p.peer);
    require_same_system(system_of(peer), system_of(twin), p.same_names);
  }
  const model::System eco9 = system_of(input::read_case(kSource + "/cases/benchmarks/eco9.bch"));
  CHECK(eco9.variables.front().name == "x_1");
  CHECK(eco9.variables.back().name == "x_8");
}

TEST_CASE("peer formats: a converted file reads back to the same system", "[peer]") {
  const std::string constants_bch = R"~(// constants, decimals, pi, vectors
Constants
  a = 0.1;
  c[2] = (1/3; -2.5e-1);
Variables
  x in [-a, 2*pi];
  v[2] in [-1e1, 1.];
Constraints
  x^2 + a*v(1) - c(2)*v[1] = sin(pi/7);
  -v(1)*v(2) + 3 = c(1)*x;
  sqr(v(2) - 0.3) = 0.01;
end
)~";
  const std::string constants_cuik = R"~([CONSTANTS]
a := 0.1
l := 8*pi
[SYSTEM VARS]
x : [-a, l]
[SECONDARY VARS]
y : [-1, 1]
[SYSTEM EQS]
x^2 + y^2 = 1.5;
[DUMMY EQS]
-x*y + a*x = 0;
)~";
  struct Source {
    std::string file, text;
  };
  std::vector<Source> sources = {{"inline.bch", constants_bch}, {"inline.cuik", constants_cuik}};
  for (const char* f : {"eco9.bch", "caprasse.bch", "kin1.bch", "cyclohexan3d.cuik"}) {
    std::ifstream in(kSource + "/cases/benchmarks/" + f);
    sources.push_back({f, std::string{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()}});
  }
  for (const Source& s : sources) {
    INFO(s.file);
    const std::string toml = input::convert_text_to_toml(s.text, s.file);
    INFO(toml);
    const input::Case back = input::read_case_text(toml, "converted.toml");
    CHECK(back.name == input::peer_case_name(s.file));
    require_same_system(read_text(s.text, s.file), system_of(back));
  }
  // Decimals are carried as written, never as the nearest double's digits.
  const std::string toml = input::convert_text_to_toml(constants_bch, "inline.bch");
  CHECK(toml.find("0.1") != std::string::npos);
  CHECK(toml.find("0.1000000") == std::string::npos);
  CHECK(toml.find("sin(pi/7)") != std::string::npos);
  CHECK(toml.find("Minibex vector v[2] is v_1 .. v_2") != std::string::npos);
  CHECK(toml.find("{ name = \"x\", domain = [\"-0.1\", \"2*pi\"] }") != std::string::npos);
}

TEST_CASE("peer formats: convert refuses what is not a peer's file", "[peer]") {
  CHECK_THROWS_AS(input::convert_to_toml(kSource + "/cases/benchmarks/kin1.toml"), InputError);
  try {
    input::convert_to_toml(kSource + "/cases/benchmarks/no-such-file.bch");
    FAIL("converted a missing file");
  } catch (const InputError& e) {
    CHECK(e.line == 0);
    CHECK(e.message == "no such file");
  }
  const std::string toml = input::convert_to_toml(kSource + "/cases/benchmarks/kin1.bch");
  CHECK(toml.find("kind = \"polynomial\"") != std::string::npos);
  CHECK(toml.find("0.4077") != std::string::npos);
}

TEST_CASE("peer formats: decimals are enclosed as written, not rounded", "[peer]") {
  const Interval tenth = rigorous::decimal("0.1");
  REQUIRE(tenth.lower() < tenth.upper());  // 0.1 is no double
  for (const auto& [file, text] : std::vector<std::pair<std::string, std::string>>{
           {"d.bch", "Constants a = 0.1; Variables x in [a, 0.3]; Constraints x - a = 0; end"},
           {"d.cuik", "[CONSTANTS] a := 0.1 [SYSTEM VARS] x : [a, 0.3] [SYSTEM EQS] x - a = 0;"}}) {
    INFO(file);
    const model::System s = read_text(text, file);
    CHECK(s.variables[0].domain.lower() == tenth.lower());
    CHECK(s.variables[0].domain.upper() == rigorous::decimal("0.3").upper());
    CHECK(same(coefficient(s.equations[0], {}), -tenth));
  }
}

TEST_CASE("peer formats: precedence, associativity and indices are the peers'", "[peer]") {
  // Minibex: '^' associates to the left, a unary minus takes the power after it, x(i) counts
  // from 1 and x[i] from 0.
  const model::System m = read_text(R"~(Variables
  x in [-2, 2];
  v[2] in [-2, 2];
Constraints
  x^2^3 = 2^3^2;
  -v(1)^2 + v[0]*v(2) = 1;
  sqr(v(2) + 1) = ln(1);
  x/(2*4) - (1 - x) = -(x + 1);
end)~",
                                    "p.bch");
  CHECK(m.equations[0].degree_in(0) == 6);  // (x^2)^3, not x^(2^3)
  CHECK(same(coefficient(m.equations[0], {}), Interval(-64.0)));
  CHECK(same(coefficient(m.equations[1], {{1, 2}}), Interval(-1.0)));  // -(v1^2), then + v1*v2
  CHECK(same(coefficient(m.equations[1], {{1, 1}, {2, 1}}), Interval(1.0)));
  CHECK(same(coefficient(m.equations[2], {{2, 1}}), Interval(2.0)));
  CHECK(boost::numeric::zero_in(coefficient(m.equations[2], {}) - Interval(1.0)));
  // The parentheses the peer's tree needs survive the translation: x/8 - 1 + x + x + 1.
  CHECK(same(coefficient(m.equations[3], {{0, 1}}), Interval(2.125)));
  CHECK(coefficient(m.equations[3], {}).upper() == 0);
  CHECK(m.equations[3].terms().size() == 1);

  // CuikSuite: in constants a unary minus binds tighter than '^' (-2^2 is 4); in equations the
  // sign belongs to the monomial (-x^2 is -(x^2)); keywords in any case; COT(x) = tan(pi/2 - x).
  const model::System c = read_text(R"~([CONSTANTS]
a := -2^2
b := cot(Pi/4)
[SYSTEM VARS]
x : [-5, 5]
[SYSTEM EQS]
-x^2 + a = 0;
x = b;
)~",
                                    "p.cuik");
  CHECK(same(coefficient(c.equations[0], {}), Interval(4.0)));
  CHECK(same(coefficient(c.equations[0], {{0, 2}}), Interval(-1.0)));
  CHECK(boost::numeric::zero_in(coefficient(c.equations[1], {}) + Interval(1.0)));
}

TEST_CASE("peer formats: the extension picks the reader", "[peer]") {
  CHECK(input::peer_reader_for("a/b/model.BCH") != nullptr);
  CHECK(input::peer_reader_for("model.Cuik") != nullptr);
  CHECK(input::peer_reader_for("model.toml") == nullptr);
  CHECK(input::peer_reader_for("dir.bch/model") == nullptr);
  CHECK(input::peer_case_name("a/b/eco9.bch") == "eco9");
  const std::string minibex = "Variables x in [0, 1]; Constraints x = 0.5; end";
  CHECK(read_text(minibex, "upper.BCH").variables.size() == 1);
  CHECK_THROWS_AS(input::read_case_text(minibex, "minibex-as.toml"), InputError);  // a TOML syntax error
}

TEST_CASE("peer formats: every malformed file is an InputError at its line", "[peer]") {
  struct Bad {
    const char* file;
    const char* text;
    int line;
    const char* message_part;
  };
  const Bad bad[] = {
      // Minibex
      {"misspelt.bch", "Variables\n  x in [0, 1];\nConstraint\n  x = 0;\nend\n", 3,
       "or 'Constraints', found 'Constraint' followed by 'x'"},
      {"undeclared.bch", "Variables\n  x in [0, 1];\nConstraints\n  x + z = 1;\nend\n", 4,
       "'z' is not declared (neither a variable nor a constant)"},
      {"semicolon.bch", "Variables\n  x in [0, 1];\n  y in [0, 1];\nConstraints\n  x + y = 1\n  x - y = 0;\nend\n", 5,
       "missing ';' after constraint 1"},
      {"semicolon-declaration.bch", "Variables\n  x in [0, 1]\n  y in [0, 1];\nConstraints\n  x = y;\nend\n", 2,
       "missing ';' after the declaration of variable 'x'"},
      {"operator.bch", "Variables\n  x in [0, 1];\nConstraints\n  2 x = 1;\nend\n", 4,
       "expected an operator, a comparison or '=' in constraint 1, found 'x'"},
      {"empty-domain.bch", "Variables\n  x in [1, 0];\nConstraints\n  x = 0;\nend\n", 2,
       "empty domain of variable 'x': lower bound exceeds upper bound"},
      {"index.bch", "Variables\n  x[4] in [-1, 1];\nConstraints\n  x(1) + x(5) = 0;\nend\n", 4,
       "index 5 is out of range for vector 'x' of 4 components"},
      {"index-from-zero.bch", "Variables\n  x[4] in [-1, 1];\nConstraints\n  x[0] + x[4] = 0;\nend\n", 4,
       "index 4 is out of range for vector 'x'"},
      {"index-fraction.bch", "Variables\n  x[4] in [-1, 1];\nConstraints\n  x(3/2) = 0;\nend\n", 4,
       "the index of 'x' must be an integer"},
      {"no-index.bch", "Variables\n  x[2] in [-1, 1];\nConstraints\n  x = 0;\nend\n", 4,
       "vector 'x' is used without an index"},
      {"for.bch", "Variables\n  x[3] in [0, 1];\nConstraints\n  for i=1:3;\n    x(i) = 0;\n  end\nend\n", 4,
       "'for' loops are not supported"},
      {"inequality.bch", "Variables\n  x in [0, 1];\nConstraints\n  x^2 <= 1;\nend\n", 4,
       "every constraint is an inequality"},
      {"ln.bch", "Variables\n  x in [0, 1];\nConstraints\n  x = 0;\n  ln(x - 5) = 0;\nend\n", 5,
       "outside the domain of log on the whole domain"},
      {"division.bch", "Variables\n  x in [-1, 1];\nConstraints\n  x = 0;\n  exp(1/x) = 2;\nend\n", 5,
       "has a divisor that may be 0 on the domain"},
      {"floor.bch", "Variables\n  x in [0, 1];\nConstraints\n  floor(x) = 1;\nend\n", 4, "function 'floor' is not supported"},
      {"atan2-one.bch", "Variables\n  x in [0, 1];\nConstraints\n  atan2(x) = 1;\nend\n", 4, "atan2"},
      {"unknown-function.bch", "Variables\n  x in [0, 1];\nConstraints\n  f(x) = 1;\nend\n", 4, "unknown function 'f'"},
      {"exponent.bch", "Variables\n  x in [0, 1];\nConstraints\n  x^2 +\n    x^(1/3) = 1;\nend\n", 5,
       "exponent must be an integer or half-integer constant"},
      {"constant-equation.bch", "Variables\n  x in [0, 1];\nConstraints\n  x = 1;\n  1 = 1;\nend\n", 5,
       "constraint 2 involves no variable"},
      {"minimize.bch", "Variables\n  x in [0, 1];\nMinimize\n  x;\nConstraints\n  x = 0;\nend\n", 3,
       "'Minimize' (an optimization goal) is not supported"},
      {"function.bch", "Variables\n  x in [0, 1];\nfunction f(y)\n  return y;\nend\nConstraints\n  x = 0;\nend\n", 3,
       "auxiliary functions ('function') are not supported"},
      {"interval-constant.bch", "Constants\n  a in [1, 0];\nVariables\n  x in [0, 1];\nConstraints\n  x = a;\nend\n", 2,
       "empty interval"},
      {"constant-count.bch", "Constants\n  c[3] = (1; 2);\nVariables\n  x in [0, 1];\nConstraints\n  x = 0;\nend\n", 2,
       "vector constant 'c' is declared with 3 components but has 2 values"},
      {"constant-division.bch",
       "Constants\n  a = 1;\n  b = pi/(a - 1);\nVariables\n  x in [0, 1];\nConstraints\n  x = b;\nend\n", 3,
       "constant 'b' (read as \"pi/(1 - 1)\"): division by an interval containing zero"},
      {"matrix.bch", "Variables\n  x[2][2] in [0, 1];\nConstraints\n  x(1) = 0;\nend\n", 2,
       "matrices ('x[m][n]') are not supported"},
      {"infinity-constant.bch", "Constants\n  a = oo;\nVariables\n  x in [0, 1];\nConstraints\n  x = a;\nend\n", 2,
       "infinity ('oo') is not supported"},
      {"duplicate.bch", "Variables\n  x in [0, 1];\n  x in [0, 2];\nConstraints\n  x = 0;\nend\n", 3,
       "'x' is already declared on line 2"},
      {"clash.bch", "Variables\n  x[2] in [0, 1];\n  x_1 in [0, 1];\nConstraints\n  x_1 = 0;\nend\n", 3,
       "variable 'x_1' clashes with component 1 of vector 'x' (line 2)"},
      {"reserved.bch", "Variables\n  log in [0, 1];\nConstraints\n  log = 0;\nend\n", 2,
       "variable name 'log' is reserved in linkbox's equations"},
      {"keyword.bch", "Variables\n  sin in [0, 1];\nConstraints\n  x = 0;\nend\n", 2, "'sin' is a reserved word"},
      {"no-constraints.bch", "Variables\n  x in [0, 1];\nConstraints\nend\n", 4, "no constraints"},
      {"missing-end.bch", "Variables\n  x in [0, 1];\nConstraints\n  x = 0;\n", 4,
       "missing 'end' after the constraints"},
      {"after-end.bch", "Variables\n  x in [0, 1];\nConstraints\n  x = 0;\nend\nx = 1;\n", 6,
       "unexpected 'x' after 'end'"},
      {"comment.bch", "Variables\n  x in [0, 1];\n/* never closed\nConstraints\n  x = 0;\nend\n", 3,
       "unterminated comment"},
      {"byte.bch", "Variables\n  x in [0, 1];\nConstraints\n  x\xC2\xB2 = 1;\nend\n", 4, "unexpected byte 0xC2"},
      {"transpose.bch", "Variables\n  x in [0, 1];\nConstraints\n  x' = 1;\nend\n", 4,
       "transposition (') is not supported"},
      {"empty.bch", "// nothing\n", 1, "expected 'Variables', found the end of the file"},
      // CuikSuite
      {"section.cuik", "[SYSTEM VARIABLES]\nx : [0, 1]\n[SYSTEM EQS]\nx = 0;\n", 1,
       "unknown section [SYSTEM VARIABLES]"},
      {"undeclared.cuik", "[SYSTEM VARS]\nx : [0, 1]\n[SYSTEM EQS]\nx + z = 1;\n", 4, "'z' is not declared"},
      {"semicolon.cuik", "[SYSTEM VARS]\nx : [0, 1]\ny : [0, 1]\n[SYSTEM EQS]\nx + y = 1\nx - y = 0;\n", 5,
       "missing ';' after equation 1"},
      {"empty-range.cuik", "[SYSTEM VARS]\nx : [1, 0]\n[SYSTEM EQS]\nx = 0;\n", 2, "empty domain of variable 'x'"},
      {"circular.cuik", "[SYSTEM VARS]\nx ~ [-pi, pi]\n[SYSTEM EQS]\nx = 0;\n", 2, "circular range ('~') of 'x'"},
      {"inequality.cuik", "[SYSTEM VARS]\nx : [0, 1]\n[SYSTEM EQS]\nx = 0;\nx^2 < 1;\n", 5,
       "expected an operator, '<=', '>=' or '=' in equation 2, found '<'"},
      {"matrix.cuik", "[SYSTEM VARS]\nx : [0, 1]\n[SYSTEM EQS]\nRX(x)*TX(1) = ID;\n", 4, "matrix equations"},
      {"parentheses.cuik", "[SYSTEM VARS]\nx : [0, 1]\n[SYSTEM EQS]\nx*(x + 1) = 0;\n", 4,
       "parentheses are not allowed in .cuik equations"},
      {"division.cuik", "[SYSTEM VARS]\nx : [0, 1]\n[SYSTEM EQS]\nx/2 = 0;\n", 4, "division is not allowed"},
      {"inf-constant.cuik", "[CONSTANTS]\na := INF\n", 2, "INF is not supported"},
      {"order.cuik", "[SYSTEM EQS]\n[SYSTEM VARS]\nx : [0, 1]\n", 2, "section [SYSTEM VARS] is out of place"},
      {"before-sections.cuik", "% comment\nx : [0, 1]\n", 2, "expected a section such as [SYSTEM VARS], found 'x'"},
      {"duplicate.cuik", "[SYSTEM VARS]\nx : [0, 1]\n[SECONDARY VARS]\nx : [0, 2]\n", 4,
       "'x' is already declared on line 2 (as a variable)"},
      {"power.cuik", "[SYSTEM VARS]\nx : [0, 1]\n[SYSTEM EQS]\nx^2.5 = 0;\n", 4,
       "'^' in a .cuik equation takes a non-negative integer"},
      {"tan.cuik", "[SYSTEM VARS]\nx : [0, 2]\n[SYSTEM EQS]\nTAN(x)*x = 1;\n", 4, "meets a pole of tan"},
      {"search.cuik", "[SYSTEM VARS]\nx : [0, 1]\n[SYSTEM EQS]\nx = 0;\n[SEARCH]\nMIN x\n", 6, "[SEARCH] MIN"},
      {"no-equations.cuik", "[SYSTEM VARS]\nx : [0, 1]\n", 2, "no equations"},
      {"velocity.cuik", "[SYSTEM VARS]\nx : [0, 1]\n[VELOCITY VARS]\n", 3, "section [VELOCITY VARS] is not supported"},
      {"range-variable.cuik", "[SYSTEM VARS]\nx : [0, 1]\ny : [0, x]\n", 3, "'x' is a variable"},
      {"conditional.cuik", "[CONSTANTS]\na := (1 > 0 ? 1 : 2)\n", 2, "comparisons ('>') are not supported"},
      {"keyword.cuik", "[SYSTEM VARS]\nPi : [0, 1]\n", 2, "'Pi' is a reserved word in .cuik files"},
      {"abs.cuik", "[CONSTANTS]\na := ABS(-1)\n", 2, "ABS is not supported"},
  };
  for (const Bad& b : bad) {
    INFO(b.file << "\n" << b.text);
    try {
      read_text(b.text, b.file);
      FAIL("read without error");
    } catch (const InputError& e) {
      INFO(e.what());
      CHECK(e.file == b.file);
      CHECK(e.line == b.line);
      CHECK(e.message.find(b.message_part) != std::string::npos);
      CHECK(std::string(e.what()) == std::string(b.file) + ":" + std::to_string(b.line) + ": " + e.message);
    }
  }
}

TEST_CASE("peer formats: deep nesting is an error, not a crash", "[peer]") {
  const std::string deep = "Variables\n  x in [0, 1];\nConstraints\n  x = " + std::string(100000, '(') + "1" +
                           std::string(100000, ')') + ";\nend\n";
  CHECK_THROWS_WITH(read_text(deep, "deep.bch"), Catch::Contains("deep.bch:4: expression nested too deeply"));
  const std::string deep_cuik = "[CONSTANTS]\na := " + std::string(100000, '-') + "1\n";
  CHECK_THROWS_WITH(read_text(deep_cuik, "deep.cuik"), Catch::Contains("deep.cuik:2: expression nested too deeply"));
  // Constants defined by constants double the text at each level: refused, not exhausted.
  std::string chain = "Constants\n  c0 = 1.5;\n";
  for (int i = 1; i <= 40; ++i)
    chain += "  c" + std::to_string(i) + " = c" + std::to_string(i - 1) + "*c" + std::to_string(i - 1) + "/c" +
             std::to_string(i - 1) + ";\n";
  chain += "Variables\n  x in [0, 1];\nConstraints\n  x = c40;\nend\n";
  CHECK_THROWS_AS(read_text(chain, "doubling.bch"), InputError);
}

namespace {

std::pair<int, std::string> run_cli(const std::string& args) {
  const test::Ran r = test::run_cli(args);
  return {r.code, r.out};
}
std::string temp(const std::string& name) { return test::scratch(name); }
using test::read_json;

std::vector<nlohmann::json> certified_boxes(const nlohmann::json& j) {
  std::vector<nlohmann::json> boxes;
  for (auto& c : j["clusters"])
    if (c["status"] == "certified") boxes.push_back(c["certificate"]["box"]);
  return boxes;
}

}  // namespace

TEST_CASE("peer formats: the CLI solves .bch and .cuik files and check re-reads them", "[peer][cli]") {
  const std::string bch_json = temp("kin1-bch.json"), toml_json = temp("kin1-toml.json");
  REQUIRE(run_cli("solve " + kSource + "/cases/benchmarks/kin1.bch --quiet --json " + bch_json).first == 0);
  REQUIRE(run_cli("solve " + kSource + "/cases/benchmarks/kin1.toml --quiet --json " + toml_json).first == 0);
  const nlohmann::json bch = read_json(bch_json), toml = read_json(toml_json);
  CHECK(bch["certified_roots"] == 16);
  CHECK(bch["certified_roots"] == toml["certified_roots"]);
  CHECK(certified_boxes(bch) == certified_boxes(toml));  // the same system, so the same search
  CHECK(run_cli("check " + bch_json).first == 0);

  const std::string cuik_json = temp("cyclohexan3d-cuik.json");
  REQUIRE(run_cli("solve " + kSource + "/cases/benchmarks/cyclohexan3d.cuik --quiet --json " + cuik_json).first == 0);
  CHECK(read_json(cuik_json)["certified_roots"] == 16);
  CHECK(run_cli("check " + cuik_json).first == 0);

  const std::string bad = temp("bad.bch");
  std::ofstream(bad) << "Variables\n  x in [0, 1];\nConstraints\n  x + z = 1;\nend\n";
  const auto [code, output] = run_cli("solve " + bad + " --quiet");
  CHECK(code == 2);
  CHECK(output.find(bad + ":4: 'z' is not declared") != std::string::npos);
}

TEST_CASE("peer formats: an unbounded domain is the default bound, stated", "[peer]") {
  const model::System m = read_text("Variables\n  x;\n  y in [0, oo];\nConstraints\n  x = y;\nend\n", "u.bch");
  REQUIRE(m.variables.size() == 2);
  CHECK(same(m.variables[0].domain, Interval(-1e8, 1e8)));
  CHECK(same(m.variables[1].domain, Interval(0, 1e8)));
  CHECK(m.assumed_bounds == std::vector<std::string>{"x in [-1e8, 1e8]", "y in [0, 1e8]"});
  const model::System c = read_text("[SYSTEM VARS]\nx : [-INF, 2]\n[SYSTEM EQS]\nx = 0;\n", "u.cuik");
  CHECK(same(c.variables[0].domain, Interval(-1e8, 2)));
  CHECK(c.assumed_bounds == std::vector<std::string>{"x in [-1e8, 2]"});
  // Bounded domains assume nothing.
  CHECK(read_text("Variables\n  x in [0, 1];\nConstraints\n  x = 0;\nend\n", "b.bch").assumed_bounds.empty());
}
