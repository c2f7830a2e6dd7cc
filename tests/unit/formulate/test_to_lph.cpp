// Polynomial -> L/P/H lifting: structure, reuse of auxiliaries, and planted roots of random
// systems lifting to points of the L/P/H system inside its domains.
#include "formulate/to_lph.hpp"

#include <catch2/catch.hpp>

#include <random>
#include <set>

using namespace linkbox;
using namespace linkbox::formulate;
using model::Polynomial;

namespace {

Polynomial var(int i) { return Polynomial::variable(i); }
Polynomial num(double c) { return Polynomial::constant(Interval(c)); }

model::System system_of(int n, std::vector<Polynomial> eqs, const Interval& domain = Interval(-2.0, 2.0)) {
  model::System s;
  for (int i = 0; i < n; ++i) s.variables.push_back({"x" + std::to_string(i), domain});
  s.equations = std::move(eqs);
  s.equation_names.assign(s.equations.size(), "");
  return s;
}

// sum coef * v - rhs over a box.
Interval residual(const model::LinearEquation& eq, const Box& box) {
  Interval r = -eq.rhs;
  for (auto& [v, c] : eq.terms) r += c * box[v];
  return r;
}

// Every dummy is defined exactly once, from variables of lower index.
void check_definitions(const model::LphSystem& lph, size_t primary) {
  std::set<int> defined;
  for (auto& p : lph.parabolic) {
    CHECK(p.x < p.q);
    CHECK(defined.insert(p.q).second);
  }
  for (auto& h : lph.hyperbolic) {
    CHECK(h.x != h.y);
    CHECK(h.x < h.b);
    CHECK(h.y < h.b);
    CHECK(defined.insert(h.b).second);
  }
  CHECK(defined.size() == lph.variables.size() - primary);
  for (int d : defined) CHECK(d >= static_cast<int>(primary));
}

}  // namespace

TEST_CASE("to_lph lifts squares, products and higher powers through shared auxiliaries", "[to_lph]") {
  // x0^3 + x0^2 x1 - 1 = 0,  x0^2 + x0 x1 x2 - x1 = 0,  x1^4 - x2 = 0
  const auto s = system_of(3, {var(0).pow(3) + var(0).pow(2) * var(1) - num(1), var(0).pow(2) + var(0) * var(1) * var(2) - var(1),
                               var(1).pow(4) - var(2)});
  std::vector<Polynomial> polys;
  const model::LphSystem lph = to_lph(s, &polys);
  REQUIRE(lph.primary == std::vector<int>{0, 1, 2});
  for (int i = 0; i < 3; ++i) CHECK(lph.variables[i].name == s.variables[i].name);
  check_definitions(lph, 3);
  // Auxiliaries: x0^2 (shared by x0^3, x0^2 x1 and eq 2), x0^3 = x0 * q, x0^2 x1 = x1 * q,
  // x1 x2, x0 x1 x2, x1^2, x1^4 = (x1^2)^2.
  std::set<std::string> names;
  for (size_t i = 3; i < lph.variables.size(); ++i) names.insert(lph.variables[i].name);
  CHECK(names == std::set<std::string>{"x0^2", "x0^3", "x0^2*x1", "x1*x2", "x0*x1*x2", "x1^2", "x1^4"});
  CHECK(lph.parabolic.size() == 3);   // x0^2, x1^2, x1^4
  CHECK(lph.hyperbolic.size() == 4);  // x0^3, x0^2 x1, x1 x2, x0 x1 x2
  REQUIRE(lph.linear.size() == 3);
  CHECK(polys.size() == 3 + 3 + 4);
  // Domains by evaluation over the original ones: x^2 in [0, 4], x^3 in [-8, 8], x^4 in [0, 16].
  for (auto& v : lph.variables) {
    if (v.name == "x0^2") CHECK((v.domain.lower() == 0 && v.domain.upper() == 4));
    if (v.name == "x0^3") CHECK((v.domain.lower() == -8 && v.domain.upper() == 8));
    if (v.name == "x1^4") CHECK((v.domain.lower() == 0 && v.domain.upper() == 16));
  }
  // Every linear equation is linear and parabolic/hyperbolic polynomials have their shape.
  for (size_t k = 0; k < 3; ++k) CHECK(polys[k].total_degree() == 1);
  for (size_t k = 3; k < polys.size(); ++k) CHECK(polys[k].total_degree() == 2);
}

TEST_CASE("to_lph keeps linear and constant equations one to one", "[to_lph]") {
  const auto s = system_of(2, {var(0) + var(1) * Interval(2.0) - num(3), num(0.5), var(1) * var(0) - var(0) * var(1)});
  const model::LphSystem lph = to_lph(s);
  REQUIRE(lph.linear.size() == 3);
  CHECK(lph.variables.size() == 2);  // x0 x1 cancels: no auxiliary
  CHECK(lph.linear[0].terms.size() == 2);
  CHECK(lph.linear[1].terms.empty());
  CHECK(contains(lph.linear[1].rhs, -0.5));
  const model::System named = lph_polynomials(lph, {"a", "b", "c"});
  CHECK(named.equation_names == std::vector<std::string>{"a", "b", "c"});
}

TEST_CASE("planted roots of random polynomial systems lift to L/P/H solutions", "[to_lph]") {
  std::mt19937 rng(2024);
  auto pick = [&](int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng); };
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  for (int trial = 0; trial < 200; ++trial) {
    const int n = pick(1, 5), m = pick(1, 5), max_degree = pick(2, 5);
    const double radius = uni(0.5, 3);
    std::vector<double> root(n);
    for (auto& r : root) r = uni(-radius, radius);
    Box point;
    for (double r : root) point.push_back(Interval(r));
    std::vector<Polynomial> eqs;
    for (int e = 0; e < m; ++e) {
      Polynomial p;
      for (int t = pick(1, 6); t > 0; --t) {
        Polynomial mono = num(uni(-3, 3));
        for (int d = pick(1, max_degree); d > 0; --d) mono = mono * var(pick(0, n - 1));
        p += mono;
      }
      // Plant the root: subtract p(root) (an interval) as the constant term.
      p -= Polynomial::constant(p.eval(point));
      eqs.push_back(std::move(p));
    }
    const model::System s = system_of(n, eqs, Interval(-radius, radius));
    std::vector<Polynomial> polys;
    const model::LphSystem lph = to_lph(s, &polys);
    check_definitions(lph, n);
    REQUIRE(lph.linear.size() == eqs.size());
    REQUIRE(polys.size() == lph.linear.size() + lph.parabolic.size() + lph.hyperbolic.size());

    const Box lifted = lift(lph, point);
    REQUIRE(lifted.size() == lph.variables.size());
    for (int i = 0; i < n; ++i) CHECK(lifted[i].lower() == root[i]);
    for (size_t v = 0; v < lifted.size(); ++v) {
      INFO("trial " << trial << " variable " << lph.variables[v].name);
      CHECK(lph.variables[v].domain.lower() <= lifted[v].lower());
      CHECK(lifted[v].upper() <= lph.variables[v].domain.upper());
    }
    for (size_t k = 0; k < polys.size(); ++k) {
      INFO("trial " << trial << " equation " << k);
      CHECK(zero_in(polys[k].eval(lifted)));
    }
    for (auto& eq : lph.linear) CHECK(zero_in(residual(eq, lifted)));
    // The original equations in terms of the lifted point agree with the linear ones.
    for (size_t k = 0; k < eqs.size(); ++k) CHECK(zero_in(eqs[k].eval(point)));
  }
}

TEST_CASE("lift pads a short box and follows definitions in any order", "[to_lph]") {
  model::LphSystem lph;
  lph.variables = {{"x", Interval(-1.0, 1.0)}, {"b", Interval(-1.0, 1.0)}, {"q", Interval(0.0, 1.0)}};
  lph.primary = {0};
  lph.parabolic.push_back({2, 0});      // q = x^2
  lph.hyperbolic.push_back({1, 0, 2});  // b = x * q, defined from a later variable
  const Box b = lift(lph, Box{Interval(0.5)});
  REQUIRE(b.size() == 3);
  CHECK(contains(b[2], 0.25));
  CHECK(contains(b[1], 0.125));
}
