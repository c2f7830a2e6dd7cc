// The operations the race prices (prune::Counters::operations): propagation and Newton cost
// what the system's structure says, the same on every box; an LP-based contractor adds each
// LP's pivots, so a larger relaxation costs more per LP.
#include "prune/hc4.hpp"
#include "prune/lp/clp_core.hpp"
#include "prune/newton_contractor.hpp"
#include "prune/taylor.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace linkbox;
using model::Polynomial;

namespace {

// f_i = sum_j (A_ij + 4 delta_ij) d_j + d_i d_{i+1}, d = x - r: a square system with root r.
std::vector<Polynomial> planted(int n, std::mt19937& rng, std::vector<double>& root) {
  std::uniform_int_distribution<int> coef(-8, 8), at(-16, 16);
  root.clear();
  for (int j = 0; j < n; ++j) root.push_back(at(rng) / 16.0);
  std::vector<Polynomial> d, f;
  for (int j = 0; j < n; ++j) d.push_back(Polynomial::variable(j) - Polynomial::constant(Interval(root[j])));
  for (int i = 0; i < n; ++i) {
    Polynomial e = d[i] * d[(i + 1) % n];
    for (int j = 0; j < n; ++j) e += d[j] * Interval(coef(rng) / 8.0 + (i == j ? 4 : 0));
    f.push_back(e);
  }
  return f;
}

Box around(const std::vector<double>& r, double w) {
  Box b;
  for (double x : r) b.push_back(Interval(x - w, x + w));
  return b;
}

// Counts are exact in double only as multiples of 1/4 (counters.hpp).
bool quarters(double x) { return std::fmod(4 * x, 1.0) == 0; }

double operations_of(const prune::Contractor& c) {
  prune::Counters k;
  c.add_work(k);
  return k.operations;
}

}  // namespace

TEST_CASE("propagation and Newton cost their structure on every box", "[operations]") {
  std::mt19937 rng(3);
  std::vector<double> root;
  const auto f = planted(7, rng, root);  // 7^3 / 4 is not a whole number
  prune::Hc4 hc4(f);
  prune::IntervalNewton newton(f, root.size());
  for (double w : {0.5, 0.01, 1e-6}) {
    Box a = around(root, w), b = a;
    const double h0 = operations_of(hc4), n0 = operations_of(newton);
    REQUIRE(hc4.contract(a) != prune::Outcome::empty);
    REQUIRE(newton.contract(b) != prune::Outcome::empty);
    CHECK(operations_of(hc4) - h0 == hc4.call_operations());
    // A box around the root: Newton reaches Gauss-Seidel, its full step.
    CHECK(operations_of(newton) - n0 == newton.step_operations());
  }
  CHECK(hc4.call_operations() > 0);
  CHECK(quarters(hc4.call_operations()));
  CHECK(quarters(newton.step_operations()));
}

TEST_CASE("an LP costs its pivots, and a larger relaxation more per LP", "[operations]") {
  std::mt19937 rng(5);
  double per_lp[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    std::vector<double> root;
    const auto f = planted(k == 0 ? 2 : 12, rng, root);
    prune::TaylorRelaxation taylor(f, root.size(), prune::lp::LpBackend::safe, Arith::verified);
    Box box = around(root, 0.25);
    REQUIRE(taylor.contract(box) != prune::Outcome::empty);
    prune::Counters c;
    taylor.add_work(c);
    REQUIRE(c.lps_solved > 0);
    CHECK(quarters(c.operations));
    CHECK(c.operations >= prune::lp::ClpCore::kPivotOperations * static_cast<double>(c.lp_iterations + c.lps_solved));
    per_lp[k] = c.operations / static_cast<double>(c.lps_solved);
  }
  CHECK(per_lp[1] > per_lp[0]);
}
