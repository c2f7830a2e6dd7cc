// Interval Newton on systems that separate: the block fallback where the whole midpoint
// Jacobian is singular, and linear definitions v = L(x) substituted out
// (prune/newton_substitution.hpp). Neither may lose a planted root, and each must narrow
// what it claims to.
#include "prune/newton_contractor.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

using namespace linkbox;
using model::Polynomial;

namespace {

Polynomial x(int i) { return Polynomial::variable(i); }
Polynomial c(double v) { return Polynomial::constant(Interval(v)); }

bool holds(const Box& box, const std::vector<double>& root) {
  for (size_t i = 0; i < root.size(); ++i)
    if (!(box[i].lower() <= root[i] && root[i] <= box[i].upper())) return false;
  return true;
}

// A box around `root` with random widths up to w, the root anywhere inside (or on a face).
Box around(const std::vector<double>& root, double w, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  Box b;
  for (double r : root) {
    const double width = w * u(rng), below = rng() % 5 == 0 ? 0 : width * u(rng);
    b.push_back(Interval(r - below, r - below + width));
  }
  return b;
}

}  // namespace

TEST_CASE("Newton narrows the regular block where another block is singular at the midpoint", "[newton]") {
  // f0 = x0^3 + x0 - 1/2 (one root, about 0.4239), f1 = x1^2 - x0 (x1 = +-sqrt(x0)): on
  // x1 in [-1, 1] the midpoint of d f1 / d x1 is 0 and the whole midpoint Jacobian singular.
  prune::IntervalNewton newton({x(0) * x(0) * x(0) + x(0) - c(0.5), x(1) * x(1) - x(0)}, 2);
  double lo = 0, hi = 1;  // the root of f0 by bisection in double
  for (int k = 0; k < 60; ++k) {
    const double m = 0.5 * (lo + hi);
    (m * m * m + m - 0.5 < 0 ? lo : hi) = m;
  }
  const auto zero_in = [](const Interval& v) { return v.lower() <= 0 && 0 <= v.upper(); };
  Box box{Interval(0, 1), Interval(-1, 1)};
  for (int k = 0; k < 6; ++k) REQUIRE(newton.contract(box) != prune::Outcome::empty);
  const Interval x0 = box[0];
  CHECK(zero_in(x0 * x0 * x0 + x0 - Interval(0.5)));  // f0 increases: its root is in box[0]
  CHECK(x0.upper() - x0.lower() < 1e-9);
  CHECK(std::fabs(x0.lower() - lo) < 1e-12);
  CHECK(box[1].lower() == -1);  // two roots of the singular block: nothing to narrow there
  CHECK(box[1].upper() == 1);
}

TEST_CASE("the block fallback loses no planted root", "[newton]") {
  // Blocks (x0, x1), (x2), (x3, x4): each row reads its block and the one before, with the
  // quadratic terms centred so that boxes around the root often hold a singular midpoint.
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> at(-8, 8);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<double> r;
    for (int i = 0; i < 5; ++i) r.push_back(at(rng) / 8.0);
    std::vector<Polynomial> d;
    for (int i = 0; i < 5; ++i) d.push_back(x(i) - c(r[i]));
    const std::vector<Polynomial> f{d[0] * d[0] + d[1] * 0.5 + d[0], d[0] * d[1] + d[1] * d[1] + d[0] - d[1],
                                    d[2] * d[2] + d[1] * d[0] + d[2], d[3] * d[3] + d[4] + d[2],
                                    d[3] * d[4] + d[4] * d[4] - d[3] + d[2] * 0.25};
    prune::IntervalNewton newton(f, 5);
    Box box = around(r, trial % 2 ? 0.1 : 2.0, rng);
    for (int k = 0; k < 4; ++k) {
      const prune::Outcome out = newton.contract(box);
      REQUIRE(out != prune::Outcome::empty);
      REQUIRE(holds(box, r));
    }
  }
}

namespace {

// Unknowns x0..x(n-1) and b_k = x_i - x_j (unknown n + k), each b_k defined by b_k - x_i + x_j
// = 0 and used squared: f_k = b_k^2 + b_{k+1} x_k - (the same at the root), as the Minibex
// reader lifts (x_i - x_j)^2.
struct Lifted {
  std::vector<Polynomial> f;
  std::vector<double> root;
  std::vector<int> sums;
};

Lifted lifted(int n, std::mt19937& rng) {
  std::uniform_int_distribution<int> at(-16, 16);
  Lifted s;
  for (int i = 0; i < n; ++i) s.root.push_back(at(rng) / 8.0);
  for (int k = 0; k < n; ++k) s.root.push_back(s.root[k] - s.root[(k + 1) % n]);
  for (int k = 0; k < n; ++k) {
    const Polynomial b = x(n + k), next = x(n + (k + 1) % n);
    const double value = s.root[n + k] * s.root[n + k] + s.root[n + (k + 1) % n] * s.root[k] + s.root[k];
    s.f.push_back(b * b + next * x(k) + x(k) - c(value));
    s.f.push_back(b - x(k) + x((k + 1) % n));
    s.sums.push_back(n + k);
  }
  return s;
}

}  // namespace

TEST_CASE("Newton with lifted sums substituted loses no planted root and costs the smaller system", "[newton]") {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 2 + trial % 5;
    const Lifted s = lifted(n, rng);
    prune::IntervalNewton substituted(s.f, 2 * n, Arith::verified, {}, s.sums), whole(s.f, 2 * n);
    CHECK(substituted.step_operations() < whole.step_operations());
    // The sums' boxes far narrower than what L gives over the x's: the expansion point's L(y)
    // then lies outside them, the case where the Jacobian must be taken over the widened box.
    Box box = around(s.root, trial % 3 == 0 ? 1e-6 : 0.5, rng);
    for (int k = n; k < 2 * n; ++k)
      if (trial % 2) box[k] = Interval(s.root[k] - 1e-3, s.root[k] + 1e-3);
    for (int step = 0; step < 4; ++step) {
      REQUIRE(substituted.contract(box) != prune::Outcome::empty);
      REQUIRE(holds(box, s.root));
    }
  }
}

TEST_CASE("Newton with lifted sums substituted converges to the root", "[newton]") {
  std::mt19937 rng(9);
  int converged = 0;
  for (int trial = 0; trial < 50; ++trial) {
    const Lifted s = lifted(3, rng);
    prune::IntervalNewton newton(s.f, 6, Arith::verified, {}, s.sums);
    Box box;
    for (double r : s.root) box.push_back(Interval(r - 1e-4, r + 1e-4));
    for (int step = 0; step < 3; ++step) REQUIRE(newton.contract(box) != prune::Outcome::empty);
    REQUIRE(holds(box, s.root));
    double widest = 0;
    for (const Interval& v : box) widest = std::max(widest, v.upper() - v.lower());
    converged += widest < 1e-6;
  }
  CHECK(converged >= 45);  // quadratic from 2e-4 wherever the system is regular at its root
}
