// Inequality constraints: parsed as g <= 0; HC4 and the LP relaxation prune with them and
// never remove a feasible point; verification certifies a root only where every inequality
// provably holds, excludes (with a re-checkable proof) roots that violate one, and reports a
// root on an inequality's boundary as such. Joint limits of linkages are inequalities too.
#include "formulate/load.hpp"
#include "tests/solved_case.hpp"
#include "formulate/to_lph.hpp"
#include "input/expression.hpp"
#include "input/input_error.hpp"
#include "interval/rigorous.hpp"
#include "prune/hc4.hpp"
#include "prune/lp/lph_relaxation.hpp"
#include "prune/lp_relaxation.hpp"
#include "report/json.hpp"
#include "solve/solve_case.hpp"
#include "verify/certify_case.hpp"
#include "verify/check.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <random>

using namespace linkbox;
using model::Polynomial;

namespace {

const std::string kSource = LINKBOX_SOURCE_DIR;

using Run = test::SolvedCase;
using test::solve_loaded;
using test::solve_text;

std::vector<std::string> check(const Run& run) { return verify::check_certificates(run.j, *run.c.formulation).failures; }

std::string circle_line(const std::string& inequalities, const std::string& line = "x - y") {
  return R"(kind = "polynomial"
name = "t"
variables = [ { name = "x", domain = [-2, 2] }, { name = "y", domain = [-2, 2] } ]
equations = [ "x^2 + y^2 - 1", ")" +
         line + R"(" ]
inequalities = [ )" + inequalities + " ]\n";
}

int count(const verify::VerifyReport& v, verify::ClusterStatus s) {
  int n = 0;
  for (auto& c : v.clusters) n += c.status == s;
  return n;
}

}  // namespace

TEST_CASE("inequalities parse as g <= 0, strict for < and >", "[inequalities][expression]") {
  std::vector<model::Application> apps;
  const std::vector<std::string> vars{"x", "y"};
  const Box at{Interval(0.5), Interval(3.0)};  // x = 1/2, y = 3
  auto g_at = [&](const char* text) { return input::parse_inequality(text, vars, apps).g.eval(at); };
  CHECK(g_at("x <= 1").lower() == -0.5);          // x - 1
  CHECK(g_at("2 > y").lower() == 1.0);            // y - 2
  CHECK(g_at("x^2 >= y + 1").lower() == 3.75);    // y + 1 - x^2
  CHECK(g_at("x < y").lower() == -2.5);           // x - y
  CHECK_FALSE(input::parse_inequality("x <= 1", vars, apps).strict);
  CHECK(input::parse_inequality("x > 1", vars, apps).strict);
  CHECK(input::parse_inequality("  x >= 1 ", vars, apps).name == "x >= 1");
  auto error = [&](const char* text, int* column = nullptr) -> std::string {
    try {
      input::parse_inequality(text, vars, apps);
    } catch (const input::ParseError& e) {
      if (column) *column = e.column;
      return e.what();
    }
    return "";
  };
  int column = -1;
  CHECK(error("x + y").find("no comparison") == 0);
  CHECK(error("x <= y <= 1", &column).find("more than one comparison") == 0);
  CHECK(column == 7);
  CHECK(error("x = 1").find("'=' in an inequality") == 0);
  CHECK(error("x =< 1") == "write <= or >=, not =< or =>");
  CHECK(error("x <= ", &column) == "empty expression");
  CHECK(column == 4);
  CHECK(error("x <= z", &column) == "unknown variable 'z'");
  CHECK(column == 5);
  // Equations may be written lhs = rhs.
  const Polynomial e = input::parse_equation("x^2 = y + 1", vars, apps);
  CHECK(e.eval(at).lower() == 0.25 - 4);
}

TEST_CASE("hc4 prunes with inequalities and never removes a feasible point", "[inequalities][hc4]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1), w(1e-9, 3);
  int emptied = 0, shrunk = 0;
  for (int c = 0; c < 2000; ++c) {
    const int n = 1 + c % 3;
    Box box(n);
    std::vector<double> point(n);
    for (int i = 0; i < n; ++i) {
      const double lo = u(rng), width = w(rng);
      box[i] = Interval(lo, lo + width);
      point[i] = rng() % 4 == 0 ? lo : std::min(lo + width * std::uniform_real_distribution<double>(0, 1)(rng), lo + width);
    }
    Box at;
    for (double p : point) at.push_back(Interval(p));
    std::vector<model::Inequality> ineqs;
    for (int e = 0; e < 1 + c % 3; ++e) {
      Polynomial g;
      for (int t = 0; t < 3; ++t) {
        Polynomial m = Polynomial::constant(Interval(u(rng)));
        for (int i = 0; i < n; ++i)
          if (rng() % 2) m = m * Polynomial::variable(i).pow(1 + rng() % 2);
        g += m;
      }
      // Feasible at the point: on the boundary (every 3rd), else strictly inside.
      const Interval v = g.eval(at);
      g -= Polynomial::constant(Interval(v.upper()) + Interval(e % 3 == 0 ? 0.0 : 0.1));
      ineqs.push_back({g, false, "g"});
    }
    prune::Hc4 h({}, Arith::verified, ineqs);
    Box b = box;
    for (int pass = 0; pass < 4; ++pass) {
      const auto o = h.contract(b);
      if (o == prune::Outcome::empty) {
        ++emptied;
        break;
      }
      shrunk += o == prune::Outcome::shrunk;
      for (int i = 0; i < n; ++i) REQUIRE(contains(b[i], point[i]));
    }
  }
  CHECK(emptied == 0);
  CHECK(shrunk > 100);

  // x^2 + y^2 <= 1 narrows [-2, 2]^2 to [-1, 1]^2 and empties a box beyond the disc.
  const Polynomial disc = Polynomial::variable(0).pow(2) + Polynomial::variable(1).pow(2) - Polynomial::constant(Interval(1.0));
  prune::Hc4 h({}, Arith::verified, {{disc, false, "disc"}});
  Box b{Interval(-2, 2), Interval(-2, 2)};
  REQUIRE(h.contract(b) == prune::Outcome::shrunk);
  CHECK(b[0].lower() >= -1.0000001);
  CHECK(b[0].upper() <= 1.0000001);
  Box out{Interval(0.8, 2), Interval(0.8, 2)};
  CHECK(h.contract(out) == prune::Outcome::empty);
  // x < 0 on [0, 1] is empty; x <= 0 leaves x = 0.
  const Polynomial x = Polynomial::variable(0);
  prune::Hc4 strict({}, Arith::verified, {{x, true, "x < 0"}}), closed({}, Arith::verified, {{x, false, "x <= 0"}});
  Box s{Interval(0, 1)}, t{Interval(0, 1)};
  CHECK(strict.contract(s) == prune::Outcome::empty);
  REQUIRE(closed.contract(t) == prune::Outcome::shrunk);
  CHECK(t[0].upper() == 0);
}

TEST_CASE("the LP relaxation has a half-space per inequality and proves an infeasible box empty",
          "[inequalities][lp]") {
  model::System s;
  s.variables = {{"x", Interval(-1, 1)}, {"y", Interval(-1, 1)}};
  s.equations = {Polynomial::variable(0).pow(2) + Polynomial::variable(1).pow(2) - Polynomial::constant(Interval(1.0))};
  const model::LphSystem plain = formulate::to_lph(s);
  s.inequalities = {{Polynomial::variable(0) * Polynomial::variable(1) - Polynomial::constant(Interval(-0.75)), false, "xy <= -3/4"}};
  const model::LphSystem with = formulate::to_lph(s);
  REQUIRE(with.inequalities.size() == 1);
  CHECK(with.hyperbolic.size() == plain.hyperbolic.size() + 1);  // x*y gets a variable
  const Box box = model::lift(with, s.domain());
  const auto rows_plain = prune::lp::build_lph_relaxation(plain, model::lift(plain, s.domain())).num_rows();
  CHECK(prune::lp::build_lph_relaxation(with, box).num_rows() > rows_plain);
  // x y <= -3/4 with x^2 + y^2 = 1 would need |x y| <= 1/2: no point, and the LP sees it on
  // the first quadrant's box.
  for (auto backend : {prune::lp::LpBackend::safe, prune::lp::LpBackend::exact}) {
    prune::LpRelaxation lp(with, backend);
    Box quadrant = model::lift(with, Box{Interval(0, 1), Interval(0, 1)});
    CHECK(lp.contract(quadrant) == prune::Outcome::empty);
    // A box holding feasible points of the equations alone stays (x y = -1/2 at (1, -1)/sqrt 2).
    prune::LpRelaxation plain_lp(plain, backend);
    Box other = model::lift(plain, Box{Interval(0, 1), Interval(-1, 0)});
    CHECK(plain_lp.contract(other) != prune::Outcome::empty);
  }
}

TEST_CASE("an inequality removes roots: the removed ones are absent, the rest certified", "[inequalities][verify]") {
  // x^2 + y^2 = 1, x = y: roots +-(1, 1)/sqrt 2; x >= 0 keeps the positive one.
  const double r = 1 / std::sqrt(2.0);
  for (auto prune : std::vector<std::string>{"hc4,newton", "lp", "hc4,newton/lp"}) {
    Run run = solve_text(circle_line(R"("x >= 0")"), prune);
    INFO(prune);
    CHECK(run.v.exact);
    CHECK(run.v.headline == "exactly 1 root in the domain where the inequality holds, each in its certified box");
    REQUIRE(run.roots.size() == 1);
    CHECK(std::fabs(median(run.roots[0][0]) - r) < 1e-14);
    CHECK(std::fabs(median(run.roots[0][1]) - r) < 1e-14);
    // The other root is nowhere: no solution box near it.
    for (auto& s : run.r.subproblems)
      for (auto& b : s.solutions) CHECK(b[0].lower() > -0.5);
    CHECK(check(run).empty());
  }
  // Newton alone ignores inequalities: the search finds both, verification excludes one with
  // a proof that `linkbox check` re-checks.
  Run newton = solve_text(circle_line(R"("x >= 0")"), "newton");
  CHECK(newton.v.exact);
  CHECK(newton.v.certified_roots == 1);
  CHECK(newton.v.infeasible == 1);
  CHECK(count(newton.v, verify::ClusterStatus::infeasible) == 1);
  CHECK(newton.v.headline.find("(1 proved to violate an inequality)") != std::string::npos);
  CHECK(check(newton).empty());
  // Forged: the excluded cluster claimed certified does not pass the check.
  nlohmann::json forged = newton.j;
  for (auto& c : forged["clusters"])
    if (c["status"] == "infeasible") c["status"] = "certified";
  forged["certified_roots"] = 2;
  bool caught = false;
  for (auto& f : verify::check_certificates(forged, *newton.c.formulation).failures)
    caught = caught || f.find("not proved to satisfy \"x >= 0\"") != std::string::npos;
  CHECK(caught);
  // Forged the other way: the certified root claimed infeasible.
  nlohmann::json flipped = newton.j;
  for (auto& c : flipped["clusters"])
    if (c["status"] == "certified") c["status"] = "infeasible";
  flipped["certified_roots"] = 0;
  CHECK_FALSE(verify::check_certificates(flipped, *newton.c.formulation).failures.empty());
}

TEST_CASE("a root exactly on an inequality's boundary is reported as such", "[inequalities][verify]") {
  // 2 x^2 = 1 exactly at the roots: both 2 x^2 >= 1 and 2 x^2 > 1 are undecided there.
  for (const char* ineq : {R"("2*x^2 >= 1", "y > 0")", R"("2*x^2 > 1", "y > 0")"}) {
    for (auto prune : std::vector<std::string>{"hc4,newton", "newton"}) {
      INFO(ineq);
      Run run = solve_text(circle_line(ineq), prune);
      CHECK_FALSE(run.v.exact);
      CHECK(run.v.certified_roots == 0);
      CHECK(run.v.unverified == 1);
      bool on_boundary = false;
      for (auto& c : run.v.clusters) {
        if (c.status != verify::ClusterStatus::unverified) continue;
        on_boundary = c.reason.find("on an inequality's boundary") != std::string::npos;
        CHECK(c.inequality == 0);
        CHECK(c.certificate.status == newton::Status::certified);  // the root itself is certified
        CHECK(contains(c.root[0], 1 / std::sqrt(2.0)));
      }
      CHECK(on_boundary);
      CHECK(run.v.headline.find("on an inequality's boundary") != std::string::npos);
      CHECK(check(run).empty());
    }
  }
}

TEST_CASE("boxes straddling an inequality are reported, boxes wholly outside are excluded", "[inequalities][verify]") {
  // y = 1 touches the circle at (0, 1): a double root, never certified. x^3 <= sin(pi)
  // holds there with equality, and sin(pi) is an enclosure of 0, not 0: the cluster
  // straddles it.
  Run straddle = solve_text(circle_line("\"x^3 <= sin(pi)\"", "y - 1"), "hc4,newton");
  REQUIRE(straddle.v.unverified == 1);
  for (auto& c : straddle.v.clusters) {
    if (c.status != verify::ClusterStatus::unverified) continue;
    CHECK(c.straddled == std::vector<int>{0});
    CHECK(c.reason.find("straddles \"x^3 <= sin(pi)\"") != std::string::npos);
  }
  // y <= 0.5 fails on all of it: with Newton alone (no inequality pruning) the cluster is
  // proved to hold no feasible root, by evaluation, and the check re-does it.
  Run outside = solve_text(circle_line(R"("y <= 0.5")", "y - 1"), "newton", 1e-4);
  CHECK(outside.v.unverified == 0);
  CHECK(count(outside.v, verify::ClusterStatus::infeasible) >= 1);
  CHECK(check(outside).empty());
}

TEST_CASE("joint limits: the roots of the unlimited linkage within the limits, certified", "[inequalities][linkage]") {
  const Run all = solve_loaded(formulate::load_case(kSource + "/cases/linkages/6r-rigid.toml"), "auto", 1e-3);
  const Run limited = solve_loaded(formulate::load_case(kSource + "/cases/linkages/6r-rigid-limits.toml"), "auto", 1e-3);
  REQUIRE(all.v.exact);
  REQUIRE(all.roots.size() == 16);
  REQUIRE(limited.v.exact);
  CHECK(check(limited).empty());
  // The limits, applied here to the reported angles: theta1 in [-pi/2, pi/2], theta4 on the
  // arc from -1.5 to 3.2 (modulo 2 pi).
  std::vector<Box> expected;
  for (auto& r : all.roots) {
    const double t1 = median(r[0]), t4 = median(r[3]);
    const double t4_on_arc = t4 < -1.5 ? t4 + 2 * M_PI : t4;
    if (std::fabs(t1) <= M_PI / 2 && t4_on_arc >= -1.5 && t4_on_arc <= 3.2) expected.push_back(r);
  }
  REQUIRE(expected.size() == 3);
  REQUIRE(limited.roots.size() == expected.size());
  for (auto& e : expected) {
    bool found = false;
    for (auto& r : limited.roots) {
      double d = 0;
      for (size_t i = 0; i < r.size(); ++i) d = std::max(d, std::fabs(median(r[i]) - median(e[i])));
      found = found || d < 1e-9;
    }
    CHECK(found);
  }
  // Every certified root satisfies the limits in the natural system, on its certified box.
  for (auto& c : limited.v.clusters) {
    if (c.status != verify::ClusterStatus::certified) continue;
    const auto& sys = limited.c.formulation->natural(c.chart);
    REQUIRE(sys.inequalities.size() == 2);
    for (auto& q : sys.inequalities) CHECK(model::side_of(q, c.certificate.box) == model::Side::inside);
  }
  const auto notes = limited.c.formulation->model_notes();
  REQUIRE(notes.size() == 1);
  CHECK(notes[0].find("2 joint limits") == 0);
}

TEST_CASE("joint limits: bad limits are InputErrors at their line", "[inequalities][linkage][input]") {
  const std::string head = R"(kind = "linkage"
name = "t"
ground = "L3"
[[loops]]
links = [
  { joint = "a", link = "L1", a = 1, d = 0, alpha = 0 },
  { joint = "b", link = "L2", a = 1, d = 0, alpha = 0 },
  { joint = "c", link = "L3", a = 1, d = 0, alpha = 0 },
  { joint = "s", type = "prismatic", theta = 0, d = [0, 1], link = "L4", a = 1, alpha = 0 },
]
[joint_limits]
)";
  struct Bad {
    const char* limit;
    const char* part;
  };
  const Bad bad[] = {
      {"z = [0, 1]", "joint limit for unknown joint 'z'"},
      {"s = [0, 1]", "is prismatic: its range is its offset d"},
      {"a = [1, 0]", "lower bound exceeds upper bound"},
      {"a = [0, 7]", "spans more than a full turn"},
      {"a = [0]", "must be an array of 2 numbers"},
      {"a = [0, \"pi/0\"]", "division by an interval containing zero"},
  };
  for (auto& b : bad) {
    INFO(b.limit);
    try {
      formulate::load_case_text(head + b.limit + "\n", "inline.toml");
      FAIL("loaded");
    } catch (const input::InputError& e) {
      CHECK(e.message.find(b.part) != std::string::npos);
      CHECK(e.line == 12);
    }
  }
  // A full turn is accepted and constrains nothing.
  const auto ok = formulate::load_case_text(head + "a = [\"-pi\", \"pi\"]\n", "inline.toml");
  CHECK(ok.formulation->natural(0).inequalities.empty());
}

TEST_CASE("an angle's domain arc is decided by the angle where its inequality is flat", "[inequalities][verify]") {
  // sin(t) = 0 has the roots 0 and pi. A domain that ends 1e-8 short of 0 (2 pi) at both ends
  // leaves 0 outside; one that reaches 1e-8 past 0 holds it. Either way the arc inequality
  // cos(t - m) >= cos(h) moves by 5e-17 there, below its enclosure's rounding: only the angle
  // of the certified box decides it.
  const auto run = [](const std::string& domain) {
    return solve_text("kind = \"polynomial\"\nname = \"t\"\nvariables = [ { name = \"t\", domain = " + domain +
                      " } ]\nequations = [ \"sin(t)\" ]\n");
  };
  Run short_of = run("[\"1e-8\", \"2*pi - 1e-8\"]");
  CHECK(short_of.v.exact);
  REQUIRE(short_of.roots.size() == 1);
  CHECK(contains(short_of.roots[0][0], M_PI));
  CHECK(count(short_of.v, verify::ClusterStatus::infeasible) == 1);
  CHECK(check(short_of).empty());
  Run past = run("[\"-1e-8\", \"2*pi - 2e-8\"]");
  CHECK(past.v.exact);
  REQUIRE(past.roots.size() == 2);
  CHECK(check(past).empty());
}

TEST_CASE("the arc's side by the angle never contradicts the angle", "[inequalities][soundness]") {
  // Random arcs and tiny boxes around points of the circle at angle phi from the centre: an
  // arc inequality said to hold has |phi| <= h, one said to fail |phi| > h.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  int decided = 0;
  for (int i = 0; i < 20000; ++i) {
    const double m = -4 + 8 * unit(rng), h = 0.1 + 3.04 * unit(rng);
    const double near = unit(rng) < 0.5 ? h : M_PI;  // near the arc's end, or its far point
    const double phi = (unit(rng) < 0.5 ? -1 : 1) * std::min(M_PI, near + 1e-6 * (2 * unit(rng) - 1));
    model::Inequality q;
    q.g = Polynomial::constant(rigorous::cos(Interval(h))) - Polynomial::variable(0) * rigorous::cos(Interval(m)) -
          Polynomial::variable(1) * rigorous::sin(Interval(m));
    q.arc = model::Inequality::Arc{0, 1, rigorous::cos(Interval(m)), rigorous::sin(Interval(m)), Interval(h),
                                   Interval(m) + Interval(-h, h)};
    const Interval u = Interval(m) + Interval(phi);
    const Interval pad(-1e-13, 1e-13);
    const model::Side side = model::side_of(q, {rigorous::cos(u) + pad, rigorous::sin(u) + pad});
    if (side == model::Side::inside) CHECK(std::fabs(phi) <= h);
    if (side == model::Side::outside) CHECK(std::fabs(phi) > h);
    decided += side != model::Side::boundary;
  }
  CHECK(decided > 15000);
}

TEST_CASE("a root exactly on an angle's domain end is proved there by its exact point", "[inequalities][verify]") {
  // sin(t) = 0 at t = 0 and 2 pi: on a domain's ends, where the certified box straddles the
  // end. Lifted, the root is the rational point (1, 0), every equation exactly 0 there, so its
  // angle is exactly 0 (mod 2 pi) and the end decides. 2 pi's upper enclosure lies above 2 pi.
  const auto run = [](const std::string& domain) {
    return solve_text("kind = \"polynomial\"\nname = \"t\"\nvariables = [ { name = \"t\", domain = " + domain +
                      " } ]\nequations = [ \"sin(t)\" ]\n");
  };
  for (const char* domain : {"[0, 3]", "[-3, 0]", "[\"0.5\", \"2*pi\"]", "[0, \"2*pi - 1e-3\"]"}) {
    INFO(domain);
    Run r = run(domain);
    CHECK(r.v.exact);
    CHECK(r.v.unverified == 0);
    bool exact_point = false;
    for (auto& cl : r.v.clusters) exact_point = exact_point || cl.exact_root == std::vector<std::string>{"1", "0"};
    CHECK(exact_point);
    CHECK(check(r).empty());
    // A stated exact root that is not the root is caught.
    for (auto& cj : r.j.at("clusters"))
      if (cj.contains("exact_root")) cj["exact_root"] = {"3/5", "4/5"};
    CHECK_FALSE(check(r).empty());
  }
  CHECK(run("[0, 3]").roots.size() == 1);
  CHECK(run("[\"0.5\", \"2*pi\"]").roots.size() == 2);  // pi and 2 pi
  CHECK(run("[0, \"2*pi - 1e-3\"]").roots.size() == 2);  // 0 and pi
  // A domain that ends a rounding short of 2 pi leaves that root outside.
  Run short_of = run("[0.5, 6.283185307179586]");
  CHECK(short_of.v.exact);
  CHECK(short_of.roots.size() == 1);
  CHECK(check(short_of).empty());
}
