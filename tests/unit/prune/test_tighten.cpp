// The LP tightening loop in both orders: over random polytopes around a planted point, each
// order keeps the point, reaches the polytope's bounding box (the exact backend's bounds, to
// rounding), and the two orders agree.
#include "prune/lp/tighten.hpp"

#include <catch2/catch.hpp>

#include <random>

using namespace linkbox;
using namespace linkbox::prune::lp;

namespace {

// Rows a.x <= a.p + slack around the planted point p, in a box [-4, 4]^n.
LinearProgram polytope(int n, const std::vector<double>& p, std::mt19937& rng) {
  std::uniform_int_distribution<int> coef(-8, 8), slack(1, 8);
  LinearProgram lp;
  for (int j = 0; j < n; ++j) lp.add_column(-4, 4);
  for (int r = 0; r < 3 * n; ++r) {
    std::vector<std::pair<int, double>> terms;
    double at = 0;
    for (int j = 0; j < n; ++j)
      if (const int c = coef(rng); c != 0) terms.push_back({j, c / 4.0}), at += c / 4.0 * p[j];
    if (!terms.empty()) lp.add_row(terms, -kInf, at + slack(rng) / 8.0);
  }
  return lp;
}

Box tightened(const LinearProgram& lp, LpBackend backend, Order order, long& lps) {
  auto solver = make_lp_solver(backend);
  solver->load(lp);
  Box box(lp.num_cols(), Interval(-4, 4));
  std::vector<int> columns(lp.num_cols());
  for (int j = 0; j < lp.num_cols(); ++j) columns[j] = j;
  REQUIRE(tighten_columns(*solver, columns, box, lps, nullptr, order));
  return box;
}

}  // namespace

TEST_CASE("LP tightening in nearest-bound order keeps the point and reaches the same box", "[lp]") {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> at(-16, 16);
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 2 + trial % 7;
    std::vector<double> p(n);
    for (double& x : p) x = at(rng) / 8.0;
    const LinearProgram lp = polytope(n, p, rng);
    long given_lps = 0, nearest_lps = 0, exact_lps = 0;
    const Box given = tightened(lp, LpBackend::safe, Order::given, given_lps);
    const Box nearest = tightened(lp, LpBackend::safe, Order::nearest_bound, nearest_lps);
    const Box exact = tightened(lp, LpBackend::exact, Order::given, exact_lps);
    INFO("trial " << trial << ", n = " << n);
    CHECK(nearest_lps <= 2 * n);
    for (int j = 0; j < n; ++j) {
      CHECK(nearest[j].lower() <= p[j]);
      CHECK(p[j] <= nearest[j].upper());
      // Both safe boxes hold the exact bounding box and lie within rounding of it.
      for (const Box* b : {&given, &nearest}) {
        CHECK((*b)[j].lower() <= exact[j].lower());
        CHECK(exact[j].upper() <= (*b)[j].upper());
        CHECK(exact[j].lower() - (*b)[j].lower() <= 1e-7);
        CHECK((*b)[j].upper() - exact[j].upper() <= 1e-7);
      }
    }
  }
}
