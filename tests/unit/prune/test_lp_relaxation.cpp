// LP-relaxation contractor: exact-rational soundness of every generated row, contraction
// toward a planted root, safe vs exact backends, proved emptiness.
#include "prune/lp/exact_lp.hpp"
#include "prune/lp/lph_relaxation.hpp"
#include "prune/lp/safe_lp.hpp"
#include "prune/lp_relaxation.hpp"
#include "formulate/load.hpp"
#include "tests/box_file.hpp"

#include <catch2/catch.hpp>
#include <gmpxx.h>

#include <ctime>
#include <cmath>
#include <random>

using namespace linkbox;
using linkbox::prune::LpRelaxation;
using linkbox::prune::Outcome;
using linkbox::prune::lp::LinearProgram;
using linkbox::prune::lp::LpBackend;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

double down(const mpq_class& q) {
  double d = q.get_d();
  while (mpq_class(d) > q) d = std::nextafter(d, -inf);
  return d;
}
double up(const mpq_class& q) {
  double d = q.get_d();
  while (mpq_class(d) < q) d = std::nextafter(d, inf);
  return d;
}
Interval enclose(const mpq_class& q) { return Interval(down(q), up(q)); }

bool inside(const Interval& range, const mpq_class& v) {
  return mpq_class(range.lower()) <= v && v <= mpq_class(range.upper());
}

// Which of the LP's rows and columns the exact point v violates (-1: none).
int violated_row(const LinearProgram& lp, const std::vector<mpq_class>& v) {
  for (int j = 0; j < lp.num_cols(); ++j)
    if (!(lp.col_lo[j] <= v[j] && v[j] <= lp.col_hi[j])) return 1000000 + j;
  for (int r = 0; r < lp.num_rows(); ++r) {
    mpq_class sum = 0;
    auto idx = lp.row_indices(r);
    auto val = lp.row_values(r);
    for (size_t k = 0; k < idx.size(); ++k) sum += mpq_class(val[k]) * v[idx[k]];
    if (lp.row_lo[r] != -inf && sum < mpq_class(lp.row_lo[r])) return r;
    if (lp.row_hi[r] != inf && sum > mpq_class(lp.row_hi[r])) return r;
  }
  return -1;
}

// x, y primary; q = x^2, b = x*y, p = y^2; one linear equation over all five.
enum Var { X, Y, Q, B, P };
model::LphSystem five_variable_system(const std::vector<Interval>& coefs, const Interval& rhs, const Box& box) {
  model::LphSystem s;
  const char* names[] = {"x", "y", "q", "b", "p"};
  for (int i = 0; i < 5; ++i) s.variables.push_back({names[i], box[i]});
  s.primary = {X, Y};
  model::LinearEquation eq;
  for (int i = 0; i < 5; ++i) eq.terms.push_back({i, coefs[i]});
  eq.rhs = rhs;
  s.linear.push_back(eq);
  s.parabolic = {{Q, X}, {P, Y}};
  s.hyperbolic = {{B, X, Y}};
  return s;
}

// Random interval [c - w/2, c + w/2] over several magnitudes of centre and width,
// including widths of 1e-12 (a few ulps at |c| ~ 1e3) and 1e6.
Interval random_range(std::mt19937& rng) {
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  const double centres[] = {uni(-2, 2), uni(-1e3, 1e3), uni(-1e-6, 1e-6), uni(1e5, 1e6)};
  const double widths[] = {1e-12, 1e-12 * 7.3, uni(0, 1), 1e6, uni(0, 1e-3)};
  double c = centres[rng() % 4], w = widths[rng() % 5];
  double lo = c - w / 2, hi = c + w / 2;
  return Interval(std::min(lo, hi), std::max(lo, hi));
}

// An exact rational point of [lo, hi]: lo + (hi - lo) k / n.
mpq_class point_in(const Interval& range, int k, int n) {
  mpq_class lo(range.lower()), hi(range.upper());
  return lo + (hi - lo) * mpq_class(k, n);
}

// The circle x^2 + y^2 = 1 written in L/P/H form: q1 + q2 = 1 plus `extra` equations.
model::LphSystem circle_system(double lo, double hi) {
  model::LphSystem s;
  s.variables = {{"x", Interval(lo, hi)}, {"y", Interval(lo, hi)}, {"q1", Interval(0, 4)}, {"q2", Interval(0, 4)}};
  s.primary = {0, 1};
  s.linear.push_back({{{2, Interval(1.0)}, {3, Interval(1.0)}}, Interval(1.0)});
  s.parabolic = {{2, 0}, {3, 1}};
  return s;
}

bool contains_root_half(const Interval& v, int sign) {  // contains sign * sqrt(1/2)?
  const mpq_class half(1, 2);
  double lo = sign * v.upper(), hi = sign * v.lower();  // mirror to the positive side
  if (sign < 0) std::swap(lo, hi), lo = -v.upper(), hi = -v.lower();
  else lo = v.lower(), hi = v.upper();
  if (hi < 0) return false;
  mpq_class l(std::max(lo, 0.0)), h(hi);
  return l * l <= half && half <= h * h;
}

}  // namespace

TEST_CASE("LPH relaxation rows hold at exact points on the surfaces (rational check)", "[lp_relaxation]") {
  std::mt19937 rng(12345);
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    Box box(5);
    box[X] = random_range(rng);
    box[Y] = random_range(rng);
    box[Q] = square(box[X]);
    box[B] = box[X] * box[Y];
    box[P] = square(box[Y]);
    // Interval coefficients: points, relative 1e-10 and wide ones.
    std::vector<Interval> coefs(5);
    for (auto& c : coefs) {
      double a = uni(-3, 3), d = std::array<double, 3>{0.0, 1e-10 * std::abs(a), 0.1}[rng() % 3];
      c = Interval(a - d, a + d);  // (rounding here is fine: the interval is the data)
    }
    const int n = 8;
    for (int k = 0; k <= n; ++k) {
      std::vector<mpq_class> v(5);
      v[X] = point_in(box[X], k, n);
      v[Y] = point_in(box[Y], int(rng() % (n + 1)), n);
      v[Q] = v[X] * v[X];
      v[B] = v[X] * v[Y];
      v[P] = v[Y] * v[Y];
      // The point satisfies the equation for a true coefficient vector inside the intervals.
      mpq_class rhs = 0;
      for (int i = 0; i < 5; ++i) rhs += point_in(coefs[i], int(rng() % 5), 4) * v[i];
      model::LphSystem system = five_variable_system(coefs, enclose(rhs), box);

      LinearProgram lp = prune::lp::build_lph_relaxation(system, box);
      INFO("trial " << trial << " box " << to_string(box));
      CHECK(lp.num_rows() >= 1 + 2 * 3 + 4);  // finite ranges: only a point x drops its middle tangent
      CHECK(violated_row(lp, v) == -1);

      Box narrowed = box;  // propagation keeps the point, and so does the relaxation after it
      REQUIRE(prune::propagate_products(system, narrowed));
      for (int i = 0; i < 5; ++i) CHECK(inside(narrowed[i], v[i]));
      CHECK(prune::linear_equations_possible(system, narrowed));
      CHECK(violated_row(prune::lp::build_lph_relaxation(system, narrowed), v) == -1);

      if (k % 4 == 0) {  // the whole contractor never loses the point
        Box contracted = box;
        LpRelaxation lp_contractor(system);
        REQUIRE(lp_contractor.contract(contracted) != Outcome::empty);
        for (int i = 0; i < 5; ++i) CHECK(inside(contracted[i], v[i]));
      }
      ++checked;
    }
  }
  CHECK(checked == 400 * 9);
}

TEST_CASE("LP relaxation contracts to the planted root of the circle and the line x = y", "[lp_relaxation]") {
  model::LphSystem s = circle_system(0.1, 2);
  s.linear.push_back({{{0, Interval(1.0)}, {1, Interval(-1.0)}}, Interval(0.0)});
  for (LpBackend backend : {LpBackend::safe, LpBackend::exact}) {
    LpRelaxation contractor(s, backend);
    Box box = s.domain();
    int iterations = 0;
    for (; iterations < 30; ++iterations) {
      Outcome o = contractor.contract(box);
      REQUIRE(o != Outcome::empty);
      REQUIRE(contains_root_half(box[0], 1));
      REQUIRE(contains_root_half(box[1], 1));
      if (o == Outcome::unchanged) break;
    }
    WARN(contractor.name() << ": " << iterations << " contractions, final x width " << width_up(box[0]));
    CHECK(width_up(box[0]) < 1e-9);
    CHECK(width_up(box[1]) < 1e-9);
  }

  // Over [-2, 2]^2 both roots (s, s) and (-s, -s) stay in the box.
  model::LphSystem both = circle_system(-2, 2);
  both.linear.push_back({{{0, Interval(1.0)}, {1, Interval(-1.0)}}, Interval(0.0)});
  LpRelaxation contractor(both);
  Box box = both.domain();
  for (int i = 0; i < 10 && contractor.contract(box) == Outcome::shrunk; ++i) {
  }
  CHECK(contains_root_half(box[0], 1));
  CHECK(contains_root_half(box[0], -1));
  CHECK(box[0].upper() < 1);  // the LP did cut the box
}

TEST_CASE("safe and exact LP backends contract to the same box", "[lp_relaxation]") {
  // x^2 + y^2 = 1 and x*y = 1/4 (four roots), variables x, y, q1, q2, b.
  model::LphSystem s = circle_system(-1.5, 1.5);
  s.variables.push_back({"b", Interval(-3, 3)});
  s.hyperbolic = {{4, 0, 1}};
  s.linear.push_back({{{4, Interval(1.0)}}, Interval(0.25)});
  std::mt19937 rng(99);
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  int compared = 0, emptied = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Box box = s.domain();
    for (int v : {0, 1}) {
      double a = uni(-1.5, 1.5), b = uni(-1.5, 1.5);
      box[v] = Interval(std::min(a, b), std::max(a, b));
    }
    Box safe_box = box, exact_box = box;
    LpRelaxation safe(s, LpBackend::safe), exact(s, LpBackend::exact);
    Outcome so = safe.contract(safe_box), eo = exact.contract(exact_box);
    INFO("trial " << trial << " box " << to_string(box));
    if (so == Outcome::empty) CHECK(eo == Outcome::empty);  // safe never empties wrongly
    REQUIRE((so == Outcome::empty) == (eo == Outcome::empty));
    if (so == Outcome::empty) {
      ++emptied;
      continue;
    }
    for (size_t i = 0; i < box.size(); ++i) {
      // Each safe bound is at most the exact one rounded outward, and its looser box only
      // loosens the later LPs, so the safe box always contains the exact box.
      CHECK(safe_box[i].lower() <= exact_box[i].lower());
      CHECK(safe_box[i].upper() >= exact_box[i].upper());
      CHECK(std::abs(safe_box[i].lower() - exact_box[i].lower()) <= 1e-9);
      CHECK(std::abs(safe_box[i].upper() - exact_box[i].upper()) <= 1e-9);
    }
    ++compared;
  }
  WARN("safe vs exact: " << compared << " contracted boxes compared, " << emptied << " emptied by both");
  CHECK(compared > 40);
}

// A real relaxation, not a random one: on this box of the bicyclohexane search, CLP with
// its default scaling called the (feasible) LP primal infeasible, and the safe backend fell
// back to the column's own bounds: two thirds of all LPs of that search lost their pruning.
// The safe bounds must be close to the exact optima.
TEST_CASE("safe LP bounds match the exact LP on a bicyclohexane relaxation", "[lp_relaxation]") {
  formulate::LoadedCase c = formulate::load_case(std::string(LINKBOX_SOURCE_DIR) + "/cases/linkages/bicyclohexane.toml");
  const formulate::SubProblem sub = c.formulation->subproblem(0);
  REQUIRE(sub.lph);
  const Box box = test::read_box_file("bicyclohexane-clp-box.txt");
  REQUIRE(box.size() == sub.lph->variables.size());
  const LinearProgram lp = prune::lp::build_lph_relaxation(*sub.lph, box);
  prune::lp::SafeLp safe;
  prune::lp::ExactLp exact;
  safe.load(lp);
  exact.load(lp);
  int tightened = 0;
  for (int k = 0; k < 3; ++k) {  // the exact LP takes up to a second each
    const int var = sub.lph->primary[k];
    INFO("variable " << var);
    const auto s_lo = safe.minimize(var), e_lo = exact.minimize(var);
    const auto s_hi = safe.maximize(var), e_hi = exact.maximize(var);
    REQUIRE(e_lo.status == prune::lp::LpStatus::bounded);
    REQUIRE(s_lo.status == prune::lp::LpStatus::bounded);
    REQUIRE(s_hi.status == prune::lp::LpStatus::bounded);
    CHECK(s_lo.value <= e_lo.value);
    CHECK(s_lo.value >= e_lo.value - 1e-6);
    CHECK(s_hi.value >= e_hi.value);
    CHECK(s_hi.value <= e_hi.value + 1e-6);
    tightened += (e_lo.value > box[var].lower() + 1e-3) + (e_hi.value < box[var].upper() - 1e-3);
  }
  CHECK(tightened > 0);  // otherwise the comparison would not show lost pruning
}

TEST_CASE("LP relaxation proves a clearly infeasible system empty", "[lp_relaxation]") {
  // x^2 + y^2 = 1 with x + y = 1.9 has no real point (max x + y on the circle is sqrt 2);
  // plain interval checks on [0,1]^2 cannot see it, one LP can.
  model::LphSystem s = circle_system(0, 1);
  s.linear.push_back({{{0, Interval(1.0)}, {1, Interval(1.0)}}, Interval(1.9)});
  Box box = s.domain();
  REQUIRE(prune::propagate_products(s, box));
  REQUIRE(prune::linear_equations_possible(s, box));
  for (LpBackend backend : {LpBackend::safe, LpBackend::exact}) {
    LpRelaxation contractor(s, backend);
    Box b = s.domain();
    CHECK(contractor.contract(b) == Outcome::empty);
  }
  // Interval propagation alone: x^2 = q with q above 1 and x in [-1, 1].
  model::LphSystem t = circle_system(-1, 1);
  t.variables[2].domain = Interval(1.5, 4);
  Box tb = t.domain();
  LpRelaxation contractor(t);
  CHECK(contractor.contract(tb) == Outcome::empty);
}

TEST_CASE("LP time per solve, safe vs exact, on a 60-column relaxation", "[.][benchmark]") {
  // 20 primaries x_i in [-1,1], q_i = x_i^2, b_i = x_i x_{i+1}; 20 random linear equations
  // through a planted root: 60 columns, 180 rows (the paper's 6R relaxation is 67 x ~200).
  std::mt19937 rng(5);
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  const int n = 20;
  model::LphSystem s;
  std::vector<double> root(3 * n);
  for (int i = 0; i < n; ++i) root[i] = uni(-0.9, 0.9);
  for (int i = 0; i < n; ++i) root[n + i] = root[i] * root[i], root[2 * n + i] = root[i] * root[(i + 1) % n];
  for (int i = 0; i < n; ++i) s.variables.push_back({"x", Interval(-1, 1)}), s.primary.push_back(i);
  for (int i = 0; i < n; ++i) s.variables.push_back({"q", Interval(0, 1)}), s.parabolic.push_back({n + i, i});
  for (int i = 0; i < n; ++i) s.variables.push_back({"b", Interval(-1, 1)}), s.hyperbolic.push_back({2 * n + i, i, (i + 1) % n});
  for (int e = 0; e < n; ++e) {
    model::LinearEquation eq;
    double value = 0;
    for (int t = 0; t < 4; ++t) {
      int v = int(rng() % (3 * n));
      double a = uni(-2, 2);
      eq.terms.push_back({v, Interval(a)});
      value += a * root[v];
    }
    eq.rhs = Interval(value - 1e-9, value + 1e-9);
    s.linear.push_back(eq);
  }
  auto time_lps = [&](prune::lp::LpSolver& solver, const LinearProgram& lp, int count) {
    // CPU time of this process: the machine is shared, wall time is not meaningful.
    std::clock_t t0 = std::clock();
    solver.load(lp);
    for (int k = 0; k < count; ++k) (k % 2 ? solver.maximize(k / 2) : solver.minimize(k / 2));
    return double(std::clock() - t0) / CLOCKS_PER_SEC / count;
  };
  for (LpBackend backend : {LpBackend::safe}) {  // whole shrinks, repeated as Algorithm 1 does
    LpRelaxation contractor(s, backend);
    Box box = s.domain();
    for (int i = 0; i < n; ++i) box[i] = Interval(root[i] - 0.05, root[i] + 0.05);
    std::clock_t t0 = std::clock();
    int shrinks = 0;
    for (; shrinks < 30 && contractor.contract(box) == Outcome::shrunk; ++shrinks) {
    }
    double seconds = double(std::clock() - t0) / CLOCKS_PER_SEC;
    WARN(contractor.name() << ": " << shrinks << " shrinks from half-width 0.05, " << seconds / contractor.lps_solved() * 1e3
                           << " ms/LP over " << contractor.lps_solved() << " LPs; final width " << max_width(box));
  }
  for (double half_width : {1.0, 1e-2, 1e-4}) {
    Box box = s.domain();
    for (int i = 0; i < n; ++i) box[i] = Interval(std::max(-1.0, root[i] - half_width), std::min(1.0, root[i] + half_width));
    REQUIRE(prune::propagate_products(s, box));
    LinearProgram lp = prune::lp::build_lph_relaxation(s, box);
    prune::lp::SafeLp safe;
    prune::lp::ExactLp exact;
    double safe_s = time_lps(safe, lp, 2 * n), exact_s = time_lps(exact, lp, 4);
    WARN("box half-width " << half_width << ": " << lp.num_cols() << " cols x " << lp.num_rows()
                           << " rows; safe " << safe_s * 1e3 << " ms/LP (" << safe.iterations()
                           << " simplex iterations for " << 2 * n << " LPs), exact " << exact_s * 1e3 << " ms/LP");
  }
}
