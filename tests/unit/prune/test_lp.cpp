// LP backends: the safe (CLP + Neumaier-Shcherbina) bound against CGAL's exact optimum.
#include "prune/lp/exact_lp.hpp"
#include "prune/lp/safe_bound.hpp"
#include "prune/lp/safe_lp.hpp"

#include <catch2/catch.hpp>
#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace linkbox::prune::lp;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

enum class Kind { general, degenerate, infeasible_pair, infeasible_range };

struct RandomLp {
  LinearProgram program;
  Kind kind;
};

// Small random LPs. Degenerate ones use small integer data and a grid point x0 (exact
// products), with many rows tight at x0, often a box vertex, and duplicated rows.
// The infeasible kinds are infeasible by a margin of 1.
RandomLp random_lp(std::mt19937& rng, Kind kind) {
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  auto pick = [&](int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng); };
  const bool exact_data = kind != Kind::general;
  RandomLp out{{}, kind};
  LinearProgram& lp = out.program;
  int n = pick(3, 8), m = pick(3, 12);
  std::vector<double> x0(n);
  for (int j = 0; j < n; ++j) {
    double lo = exact_data ? pick(-8, 4) : uni(-10, 5);
    double hi = lo + (exact_data ? pick(0, 6) : uni(0.1, 10));
    lp.add_column(lo, hi);
    if (kind == Kind::degenerate && pick(0, 1)) x0[j] = pick(0, 1) ? lo : hi;  // vertex coordinates
    else x0[j] = exact_data ? lo + (hi - lo) * pick(0, 8) / 8.0 : uni(lo, hi);
  }
  auto random_row = [&] {
    std::vector<std::pair<int, double>> row;
    for (int j = 0; j < n; ++j)
      if (pick(0, 9) < 6) row.push_back({j, exact_data ? double(pick(-5, 5)) : uni(-5, 5)});
    if (row.empty()) row.push_back({pick(0, n - 1), 1.0});
    return row;
  };
  auto dot = [&](const std::vector<std::pair<int, double>>& row) {
    double v = 0;
    for (auto& [j, a] : row) v += a * x0[j];
    return v;
  };
  std::vector<std::pair<int, double>> last;
  for (int i = 0; i < m; ++i) {
    auto row = (kind == Kind::degenerate && i > 0 && pick(0, 3) == 0) ? last : random_row();
    double v = dot(row);
    double below = exact_data ? (pick(0, 2) ? 0.0 : pick(1, 3)) : uni(0, 3);
    double above = exact_data ? (pick(0, 2) ? 0.0 : pick(1, 3)) : uni(0, 3);
    int sides = pick(0, 3);
    double lo = sides == 1 ? -inf : v - below;
    double hi = sides == 2 ? inf : v + above;
    lp.add_row(row, lo, hi);
    last = row;
  }
  if (kind == Kind::infeasible_pair) {  // a.x >= t + 1 and a.x <= t, both inside a.X
    auto row = random_row();
    double t = dot(row);
    lp.add_row(row, t + 1, inf);
    lp.add_row(row, -inf, t);
  }
  if (kind == Kind::infeasible_range) {  // a.x >= max over the box + 1
    auto row = random_row();
    double top = 0;
    for (auto& [j, a] : row) top += a > 0 ? a * lp.col_hi[j] : a * lp.col_lo[j];
    lp.add_row(row, top + 1, inf);
  }
  return out;
}

double tolerance(double exact) { return 1e-9 * (1 + std::abs(exact)); }

}  // namespace

TEST_CASE("hand LP: safe and exact agree with the known optimum", "[lp]") {
  // x in [-10,10], y in [0,10]; x + y <= 4, y - x <= 2, x + 2y >= 3.
  // min x = -1/3 (not a double), max x = 4, min y = 0, max y = 3.
  LinearProgram lp;
  int x = lp.add_column(-10, 10), y = lp.add_column(0, 10);
  lp.add_row({{x, 1}, {y, 1}}, -inf, 4);
  lp.add_row({{x, -1}, {y, 1}}, -inf, 2);
  lp.add_row({{x, 1}, {y, 2}}, 3, inf);

  ExactLp exact;
  exact.load(lp);
  LpBound e = exact.minimize(x);
  REQUIRE(e.status == LpStatus::bounded);
  const mpq_class third(-1, 3);  // -1/3 is not a double: the exact result is rounded down
  CHECK(mpq_class(e.value) < third);
  CHECK(mpq_class(std::nextafter(e.value, inf)) > third);
  CHECK(exact.maximize(x).value == 4);
  CHECK(exact.minimize(y).value == 0);
  CHECK(exact.maximize(y).value == 3);

  SafeLp safe;
  safe.load(lp);
  for (int rep = 0; rep < 2; ++rep) {  // the second round runs warm-started
    LpBound s = safe.minimize(x);
    REQUIRE(s.status == LpStatus::bounded);
    CHECK(s.value <= e.value);
    CHECK(s.value > e.value - 1e-12);
    LpBound s_max = safe.maximize(x);
    CHECK(s_max.value >= 4);
    CHECK(s_max.value < 4 + 1e-12);
    CHECK(safe.minimize(y).value <= 0);
    CHECK(safe.minimize(y).value > -1e-12);
    CHECK(safe.maximize(y).value >= 3);
    CHECK(safe.maximize(y).value < 3 + 1e-12);
  }

  // Tightening a column bound after the fact is seen by the next solve.
  safe.set_column_bounds(x, 0, 10);
  exact.set_column_bounds(x, 0, 10);
  CHECK(exact.maximize(y).value == 3);
  CHECK(safe.minimize(x).value <= 0);
  CHECK(safe.minimize(x).value > -1e-12);
}

TEST_CASE("N-S bound is valid for any multipliers, and tight for the optimal dual", "[lp]") {
  // min x subject to x + y >= 1, x - y >= 0 (x,y in [-5,5]): optimum x = 1/2, dual (1/2, 1/2).
  LinearProgram lp;
  lp.add_column(-5, 5);
  lp.add_column(-5, 5);
  lp.add_row({{0, 1}, {1, 1}}, 1, inf);
  lp.add_row({{0, 1}, {1, -1}}, 0, inf);
  const std::pair<int, double> objective[] = {{0, 1.0}};
  const double optimal[] = {0.5, 0.5};
  CHECK(dual_lower_bound(lp, optimal, objective) == 0.5);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> garbage(-3, 3);
  for (int k = 0; k < 1000; ++k) {
    const double y[] = {garbage(rng), garbage(rng)};
    CHECK(dual_lower_bound(lp, y, objective) <= 0.5);
  }
  const double nan_y[] = {std::nan(""), 0.5};
  CHECK(dual_lower_bound(lp, nan_y, objective) <= 0.5);

  // Farkas: x + y >= 3 and x + y <= 1 (x,y in [-5,5]); y = (1, -1) certifies.
  LinearProgram bad;
  bad.add_column(-5, 5);
  bad.add_column(-5, 5);
  bad.add_row({{0, 1}, {1, 1}}, 3, inf);
  bad.add_row({{0, 1}, {1, 1}}, -inf, 1);
  const double ray[] = {1, -1}, wrong[] = {-1, 1};
  CHECK(proves_infeasible(bad, ray));
  CHECK_FALSE(proves_infeasible(bad, wrong));
  CHECK_FALSE(proves_infeasible(lp, optimal));
}

TEST_CASE("random small LPs: safe bound never beats the exact optimum and is within 1e-9", "[lp]") {
  std::mt19937 rng(20240611);
  const Kind kinds[] = {Kind::general, Kind::degenerate, Kind::infeasible_pair, Kind::infeasible_range};
  int feasible = 0, infeasible = 0, safe_unknown_on_infeasible = 0;
  double worst_gap = 0;
  for (int trial = 0; trial < 400; ++trial) {
    Kind kind = kinds[trial % 4];
    RandomLp r = random_lp(rng, kind);
    const LinearProgram& lp = r.program;
    ExactLp exact;
    SafeLp safe;
    exact.load(lp);
    safe.load(lp);
    const bool clearly_infeasible = kind == Kind::infeasible_pair || kind == Kind::infeasible_range;
    for (int j = 0; j < lp.num_cols(); ++j) {
      for (int dir = 0; dir < 2; ++dir) {
        LpBound e = dir == 0 ? exact.minimize(j) : exact.maximize(j);
        LpBound s = dir == 0 ? safe.minimize(j) : safe.maximize(j);
        INFO("trial " << trial << " kind " << int(kind) << " col " << j << " dir " << dir);
        if (clearly_infeasible) REQUIRE(e.status == LpStatus::infeasible);
        // Soundness: safe may only say infeasible when it is.
        if (s.status == LpStatus::infeasible) REQUIRE(e.status == LpStatus::infeasible);
        if (e.status == LpStatus::infeasible) {
          ++infeasible;
          if (clearly_infeasible) CHECK(s.status == LpStatus::infeasible);
          if (s.status == LpStatus::unknown) ++safe_unknown_on_infeasible;
          continue;
        }
        ++feasible;
        REQUIRE(e.status == LpStatus::bounded);
        REQUIRE(s.status == LpStatus::bounded);
        if (dir == 0) CHECK(s.value <= e.value);
        else CHECK(s.value >= e.value);
        double gap = std::abs(s.value - e.value);
        worst_gap = std::max(worst_gap, gap / (1 + std::abs(e.value)));
        CHECK(gap <= tolerance(e.value));
      }
    }
  }
  WARN("random LPs: " << feasible << " feasible / " << infeasible << " infeasible objectives, safe unknown on "
                      << safe_unknown_on_infeasible << ", worst relative gap " << worst_gap);
  CHECK(feasible > 500);
  CHECK(infeasible > 500);
}
