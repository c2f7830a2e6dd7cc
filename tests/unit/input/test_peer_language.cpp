// The peers' readers speak the TOML polynomial case's language: functions of variables lifted,
// inequalities, interval constants; and what they still refuse is refused at its line with
// the feature named (a bounded domain suggested where one is missing).
#include "input/case_file.hpp"
#include "input/expression.hpp"
#include "input/to_toml.hpp"
#include "interval/rigorous.hpp"
#include "model/lifting.hpp"

#include <catch2/catch.hpp>

#include <string>

using namespace linkbox;
using input::InputError;

namespace {

bool same(const Interval& a, const Interval& b) { return a.lower() == b.lower() && a.upper() == b.upper(); }

model::System read(const std::string& text, const std::string& file) {
  const input::Case c = input::read_case_text(text, file);
  REQUIRE(std::holds_alternative<model::System>(c.description));
  return std::get<model::System>(c.description);
}

Interval coefficient(const model::Polynomial& p, const model::Powers& powers) {
  auto it = p.terms().find(powers);
  return it == p.terms().end() ? Interval(0.0) : it->second;
}

// Same unknowns, domains, equations and inequalities, coefficient for coefficient.
void require_same(const model::System& a, const model::System& b) {
  REQUIRE(a.names() == b.names());
  for (size_t i = 0; i < a.variables.size(); ++i) CHECK(same(a.variables[i].domain, b.variables[i].domain));
  REQUIRE(a.equations.size() == b.equations.size());
  for (size_t i = 0; i < a.equations.size(); ++i) CHECK(model::same(a.equations[i], b.equations[i]));
  REQUIRE(a.links.size() == b.links.size());
  for (size_t i = 0; i < a.links.size(); ++i)
    CHECK((a.links[i].f == b.links[i].f && a.links[i].y == b.links[i].y && a.links[i].a == b.links[i].a));
  REQUIRE(a.inequalities.size() == b.inequalities.size());
  for (size_t i = 0; i < a.inequalities.size(); ++i) {
    CHECK(model::same(a.inequalities[i].g, b.inequalities[i].g));
    CHECK(a.inequalities[i].strict == b.inequalities[i].strict);
    CHECK(a.inequalities[i].name == b.inequalities[i].name);
  }
  CHECK(a.interval_constants == b.interval_constants);
  CHECK(static_cast<bool>(a.lifting) == static_cast<bool>(b.lifting));
}

// The peer's file, and its converted TOML read back: the same system.
model::System read_and_convert(const std::string& text, const std::string& file) {
  const model::System s = read(text, file);
  const std::string toml = input::convert_text_to_toml(text, file);
  INFO(toml);
  require_same(s, read(toml, "converted.toml"));
  return s;
}

struct Refusal {
  const char* file;
  const char* text;
  int line;
  const char* part;
};

void check_refused(const Refusal& r) {
  INFO(r.file << "\n" << r.text);
  try {
    read(r.text, r.file);
    FAIL("read without error");
  } catch (const InputError& e) {
    INFO(e.what());
    CHECK(e.line == r.line);
    CHECK(e.message.find(r.part) != std::string::npos);
  }
}

}  // namespace

TEST_CASE("peer language: sin, cos, tan and sqrt of variables are lifted as in TOML", "[peer][functions]") {
  const model::System s = read_and_convert(R"~(Variables
  t in [0, pi/2];
  x in [0, 4];
Constraints
  cos(t) + sin(t) = 1.2;
  sqrt(x) = 2*sin(t);
end
)~",
                                           "trig.bch");
  REQUIRE(s.lifting);
  CHECK(s.lifting->declared.size() == 2);
  CHECK(s.variables.size() > 2);

  const model::System c =
      read_and_convert("[SYSTEM VARS]\nt : [-1, 1]\n[SYSTEM EQS]\nSIN(t) + COS(t) = 1.2;\n", "trig.cuik");
  REQUIRE(c.lifting);
  CHECK(c.lifting->declared.size() == 1);
}

TEST_CASE("peer language: exp, ln, sinh and divisions of variables are lifted as in TOML", "[peer][functions]") {
  const model::System s = read_and_convert(R"~(Variables
  x in [0, 1];
  y in [1, 2];
Constraints
  exp(x - y) * x + ln(y) = 1;
  sinh(x) / (y + x^2) + sin(x) * x = 0.5;
end
)~",
                                           "links.bch");
  REQUIRE(s.lifting);
  CHECK(s.links.size() == 4);  // exp, log, sinh, sin (x occurs outside sin)
  CHECK(s.variables.size() == 2 + 4 + 1 + 1);  // the links' y, exp's argument x - y, 1/(y + x^2)
}

TEST_CASE("peer language: inequalities among the constraints", "[peer][inequalities]") {
  const model::System s = read_and_convert(R"~(Variables
  x in [-2, 2];
  y in [-2, 2];
Constraints
  x^2 + y^2 = 1;
  x + y <= 1;
  y > 0;
  x - y = 0;
end
)~",
                                           "ineq.bch");
  CHECK(s.equations.size() == 2);
  REQUIRE(s.inequalities.size() == 2);
  CHECK_FALSE(s.inequalities[0].strict);
  CHECK(s.inequalities[0].name == "x + y <= 1");
  CHECK(s.inequalities[1].strict);
  const std::string toml = input::convert_text_to_toml("Variables x in [0, 1]; Constraints x^2 = 0.5; x >= 0.1; end",
                                                       "one.bch");
  CHECK(toml.find("inequalities = [\n  \"x >= 0.1\",\n]") != std::string::npos);

  const model::System c = read_and_convert(
      "[SYSTEM VARS]\nx : [-2, 2]\ny : [-2, 2]\n[SYSTEM EQS]\nx^2 + y^2 = 1;\nx*y >= 0.25;\nx - y = 0;\n", "ineq.cuik");
  CHECK(c.equations.size() == 2);
  CHECK(c.inequalities.size() == 1);
}

TEST_CASE("peer language: point intervals are plain constants", "[peer][interval-constants]") {
  const model::System s = read_and_convert(R"~(Constants
  f in 0;
  h in 1/7;
  c in [2, 2];
  d in [0.5, 1/2];
Variables
  x in [-1, 1];
Constraints
  h*x^2 + c*x - d = f;
end
)~",
                                           "point.bch");
  CHECK(s.interval_constants.empty());
  CHECK(same(coefficient(s.equations[0], {{0, 2}}), Interval(1.0) / Interval(7.0)));
  CHECK(same(coefficient(s.equations[0], {{0, 1}}), Interval(2.0)));
  CHECK(same(coefficient(s.equations[0], {}), Interval(-0.5)));
  // A point interval may bound a domain, as the number it is.
  CHECK(read("Constants c in [2, 2]; Variables x in [-c, c]; Constraints x = 1; end", "b.bch").variables[0].domain.upper() ==
        2);
}

TEST_CASE("peer language: a genuine interval constant is an interval coefficient", "[peer][interval-constants]") {
  const std::string bch = R"~(Constants
  c in [0.9, 1.1];
  k = 2*c;
Variables
  x in [-2, 2];
Constraints
  c*x^2 - k = [-0.5, 0.5];
end
)~";
  const model::System s = read_and_convert(bch, "thick.bch");
  CHECK(s.interval_constants == std::vector<std::string>{"[0.9, 1.1]", "[-0.5, 0.5]"});
  const Interval a = coefficient(s.equations[0], {{0, 2}});
  CHECK(a.lower() == rigorous::decimal("0.9").lower());
  CHECK(a.upper() == rigorous::decimal("1.1").upper());
  // -2c - [-0.5, 0.5]: every value of both.
  const Interval b = coefficient(s.equations[0], {});
  CHECK(b.lower() <= -2.7);
  CHECK(b.upper() >= -1.3);
  const std::string toml = input::convert_text_to_toml(bch, "thick.bch");
  CHECK(toml.find("Minibex constant 'c' is the interval [0.9, 1.1]") != std::string::npos);

  // TOML cases take them in equations and inequalities, never in domains.
  const model::System t = read(R"~(kind = "polynomial"
name = "t"
variables = [ { name = "x", domain = [0, 2] } ]
equations = [ "[1, 2]*x - 1" ]
inequalities = [ "x <= [1.5, 1.6]" ]
)~",
                               "t.toml");
  CHECK(t.interval_constants == std::vector<std::string>{"[1, 2]", "[1.5, 1.6]"});
  CHECK(same(coefficient(t.equations[0], {{0, 1}}), Interval(1.0, 2.0)));
  CHECK_THROWS_AS(input::parse_constant("[1, 2]"), input::ParseError);
  input::IntervalConstants listed;
  CHECK(same(input::parse_constant("[1, 2] + [3, 3]", &listed), Interval(4.0, 5.0)));
  CHECK(listed == std::vector<std::string>{"[1, 2]"});
}

TEST_CASE("peer language: what stays refused is refused at its line", "[peer]") {
  const Refusal refusals[] = {
      {"ln.bch", "Variables\n  x in [0, 1];\nConstraints\n  x = 0.5;\n  ln(x - 2) = 2;\nend\n", 5,
       "outside the domain of log on the whole domain"},
      {"mixed-angle.bch", "Variables\n  t in [0, 2];\nConstraints\n  tan(t) + t = 1;\nend\n", 4, "meets a pole of tan"},
      {"interval-domain.bch", "Constants\n  c in [1, 2];\nVariables\n  x in [0, c];\nConstraints\n  x = 1;\nend\n", 4,
       "an interval constant ('[a, b]') is allowed only in equations and inequalities"},
      {"interval-size.bch", "Constants\n  n in [1, 2];\nVariables\n  x[n] in [0, 1];\nConstraints\n  x(1) = 1;\nend\n",
       4, "interval constant"},
      {"empty-interval.bch", "Constants\n  c in [2, 1];\nVariables\n  x in [0, 1];\nConstraints\n  x = c;\nend\n", 2,
       "empty interval"},
      {"vector-interval.bch",
       "Constants\n  c[2] in [0, 1];\nVariables\n  x in [0, 1];\nConstraints\n  x = c(1);\nend\n", 2,
       "only scalar interval constants"},
      {"interval-variable.bch", "Variables\n  x in [0, 1];\nConstraints\n  x = [0, x];\nend\n", 4,
       "must be a constant expression"},
      {"only-inequalities.bch", "Variables\n  x in [0, 1];\nConstraints\n  x <= 0.5;\n  x >= 0.1;\nend\n", 4,
       "every constraint is an inequality"},
      {"thick-equation.bch", "Variables\n  x in [0, 1];\nConstraints\n  x^2 in [0, 1];\nend\n", 4,
       "constraints 'in' an interval (thick equations) are not supported"},
      {"constant-inequality.bch", "Variables\n  x in [0, 1];\nConstraints\n  x = 0.5;\n  1 <= 2;\nend\n", 5,
       "constraint 2 involves no variable"},
      {"chained.bch", "Variables\n  x in [0, 1];\nConstraints\n  0 <= x <= 1;\nend\n", 4, "a second comparison"},
      {"mixed-angle.cuik", "[SYSTEM VARS]\nt : [-2, 2]\n[SYSTEM EQS]\nTAN(t) + t^2 = 0.5;\n", 4, "meets a pole of tan"},
  };
  for (const Refusal& r : refusals) check_refused(r);
}
