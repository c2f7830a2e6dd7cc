// The Taylor (corner) relaxation: every row holds at a planted root, checked in rationals;
// contraction never loses the root (safe and exact backends) and closes in on it.
#include "prune/taylor.hpp"

#include <catch2/catch.hpp>
#include <gmpxx.h>

#include <random>

using namespace linkbox;
using linkbox::prune::Outcome;
using linkbox::prune::TaylorRelaxation;
using linkbox::prune::lp::LinearProgram;
using linkbox::prune::lp::LpBackend;

namespace {

using model::Polynomial;

// A random quadratic system with the root r: f_i = sum_j A_ij d_j + sum_{j<=k} B_ijk d_j d_k,
// d = x - r, expanded. Every number is a small dyadic rational, so every coefficient is exact.
struct Planted {
  std::vector<Polynomial> equations;
  std::vector<double> root;
};

// The first `linear` equations have no quadratic part.
Planted planted(int n, std::mt19937& rng, int linear = 0) {
  std::uniform_int_distribution<int> coef(-16, 16), at(-24, 24);
  Planted p;
  for (int j = 0; j < n; ++j) p.root.push_back(at(rng) / 16.0);
  std::vector<Polynomial> d;
  for (int j = 0; j < n; ++j) d.push_back(Polynomial::variable(j) - Polynomial::constant(Interval(p.root[j])));
  for (int i = 0; i < n; ++i) {
    Polynomial f;
    for (int j = 0; j < n; ++j) {
      f += d[j] * Interval(coef(rng) / 8.0 + (i == j ? 4 : 0));
      if (i >= linear)
        for (int k = j; k < n; ++k) f += d[j] * d[k] * Interval(coef(rng) / 8.0);
    }
    p.equations.push_back(f);
  }
  return p;
}

// A box around r: each side from r - a/16 to r + b/16, a, b in 0..most.
Box box_around(const std::vector<double>& r, std::mt19937& rng, int most = 32) {
  std::uniform_int_distribution<int> reach(0, most);
  Box box;
  for (double x : r) box.push_back(Interval(x - reach(rng) / 16.0, x + reach(rng) / 16.0));
  return box;
}

bool holds_exactly(const LinearProgram& lp, int row, const std::vector<double>& x) {
  mpq_class sum = 0;
  const auto cols = lp.row_indices(row);
  const auto vals = lp.row_values(row);
  for (size_t k = 0; k < cols.size(); ++k) sum += mpq_class(vals[k]) * mpq_class(x[cols[k]]);
  const bool above = !std::isfinite(lp.row_lo[row]) || mpq_class(lp.row_lo[row]) <= sum;
  const bool below = !std::isfinite(lp.row_hi[row]) || sum <= mpq_class(lp.row_hi[row]);
  return above && below;
}

bool holds(const Box& box, const std::vector<double>& x) {
  for (size_t j = 0; j < x.size(); ++j)
    if (!contains(box[j], x[j])) return false;
  return true;
}

}  // namespace

TEST_CASE("Taylor relaxation rows hold at the planted root (rational check)", "[taylor]") {
  std::mt19937 rng(7);
  long rows = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Planted p = planted(2 + trial % 4, rng);
    TaylorRelaxation taylor(p.equations, p.root.size(), LpBackend::safe, Arith::verified);
    const Box box = box_around(p.root, rng);
    LinearProgram lp;
    REQUIRE(taylor.relax(box, lp));  // a root inside: no row's range misses 0
    for (int r = 0; r < lp.num_rows(); ++r) {
      INFO("trial " << trial << " row " << r);
      REQUIRE(holds_exactly(lp, r, p.root));
    }
    rows += lp.num_rows();
  }
  CHECK(rows > 0);
}

TEST_CASE("Taylor relaxation: a linear equation is one ranged row that holds at the root", "[taylor]") {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 2 + trial % 4, linear = 1 + trial % (n - 1);
    const Planted p = planted(n, rng, linear);
    TaylorRelaxation taylor(p.equations, p.root.size(), LpBackend::safe, Arith::verified);
    const Box box = box_around(p.root, rng);
    LinearProgram lp;
    REQUIRE(taylor.relax(box, lp));
    // Linear rows: one slab each; the others: two rows at each of the two corners.
    CHECK(lp.num_rows() == linear + 4 * (n - linear));
    int ranged = 0;
    for (int r = 0; r < lp.num_rows(); ++r) {
      INFO("trial " << trial << " row " << r);
      REQUIRE(holds_exactly(lp, r, p.root));
      ranged += std::isfinite(lp.row_lo[r]) && std::isfinite(lp.row_hi[r]);
    }
    CHECK(ranged == linear);
    Box contracted = box;
    for (int pass = 0; pass < 10 && taylor.contract(contracted) == Outcome::shrunk; ++pass) REQUIRE(holds(contracted, p.root));
    REQUIRE(holds(contracted, p.root));
  }
}

TEST_CASE("Taylor relaxation keeps the planted root and closes in on it", "[taylor]") {
  std::mt19937 rng(11);
  for (LpBackend backend : {LpBackend::safe, LpBackend::exact}) {
    int shrunk = 0, tight = 0;
    for (int trial = 0; trial < 30; ++trial) {
      const Planted p = planted(2 + trial % 3, rng);
      TaylorRelaxation taylor(p.equations, p.root.size(), backend, Arith::verified);
      Box box = box_around(p.root, rng, trial % 2 ? 32 : 8);
      for (int pass = 0; pass < 40; ++pass) {
        const Outcome o = taylor.contract(box);
        INFO("trial " << trial << " pass " << pass);
        REQUIRE(o != Outcome::empty);
        REQUIRE(holds(box, p.root));
        shrunk += o == Outcome::shrunk;
        if (o == Outcome::unchanged) break;
      }
      tight += max_width(box) < 1e-6;
    }
    // The Jacobian is near 4 I on the narrower boxes (half of them), where the relaxation
    // closes in on the root as Newton would.
    CHECK(shrunk > 30);
    CHECK(tight >= 12);
  }
}
