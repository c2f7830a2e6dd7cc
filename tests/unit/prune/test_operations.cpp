// The operations the race prices (prune::Counters::operations): propagation and Newton cost
// what the system's structure says, the same on every box; an LP-based contractor adds each
// LP's pivots, so a larger relaxation costs more per LP.
#include "model/compiled.hpp"
#include "model/link.hpp"
#include "prune/hc4.hpp"
#include "prune/lp/clp_core.hpp"
#include "prune/newton_contractor.hpp"
#include "prune/sequence.hpp"
#include "prune/taylor.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <stdexcept>

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

TEST_CASE("a Newton step that finds its midpoint Jacobian singular costs only its LU", "[operations]") {
  // f = (x0^2 + x1^2 - 1/2, x0 x1 - 1/8) on [-1, 1]^2: the midpoint Jacobian (2 x0, 2 x1; x1,
  // x0) is 0, so the step stops after the LU, before the inverse and Gauss-Seidel it would
  // otherwise pay for. Both equations hold both unknowns: one block, no block fallback.
  const Polynomial x0 = Polynomial::variable(0), x1 = Polynomial::variable(1);
  prune::IntervalNewton newton(
      {x0 * x0 + x1 * x1 - Polynomial::constant(Interval(0.5)), x0 * x1 - Polynomial::constant(Interval(0.125))}, 2);
  Box box{Interval(-1, 1), Interval(-1, 1)};
  REQUIRE(newton.contract(box) == prune::Outcome::unchanged);
  const double spent = operations_of(newton);
  CHECK(spent > 0);
  CHECK(spent < newton.step_operations());
  CHECK(quarters(spent));
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

TEST_CASE("a sequence's live count advances within a call, so a cap can stop it there", "[operations]") {
  // The race's box cap (solve/search_step.cpp) is asked between the LPs of one pass: it reads
  // Sequence::live_operations, which must count the call under way.
  std::mt19937 rng(7);
  std::vector<double> root;
  const auto f = planted(12, rng, root);
  auto sequence_of = [&] {
    std::vector<std::unique_ptr<prune::Contractor>> m;
    m.push_back(std::make_unique<prune::TaylorRelaxation>(f, root.size(), prune::lp::LpBackend::safe, Arith::verified));
    std::vector<int> dims(root.size());
    for (size_t j = 0; j < dims.size(); ++j) dims[j] = static_cast<int>(j);
    return std::make_unique<prune::Sequence>(std::move(m), dims);
  };
  const auto whole_ptr = sequence_of();
  prune::Sequence& whole = *whole_ptr;
  std::vector<double> seen;
  const std::function<bool()> watch = [&] { return seen.push_back(whole.live_operations()), false; };
  whole.stop_when(&watch);
  Box a = around(root, 0.25);
  REQUIRE(whole.contract(a) != prune::Outcome::empty);
  const double full = whole.operations();
  REQUIRE(seen.size() > 2);
  CHECK(std::is_sorted(seen.begin(), seen.end()));
  CHECK(seen.back() > seen.front());
  CHECK(seen.back() <= full);
  CHECK(whole.live_operations() == full);  // between calls, the counters alone

  const auto cut_ptr = sequence_of();
  prune::Sequence& cut = *cut_ptr;
  const std::function<bool()> cap = [&] { return cut.live_operations() > full / 4; };
  cut.stop_when(&cap);
  Box b = around(root, 0.25);
  cut.contract(b);
  CHECK(cut.operations() < full / 2);

  // A call that throws (here from its stop request) leaves no call under way.
  const auto thrown_ptr = sequence_of();
  prune::Sequence& thrown = *thrown_ptr;
  int asked = 0;
  const std::function<bool()> fail = [&]() -> bool {
    if (++asked == 3) throw std::runtime_error("stop");
    return false;
  };
  thrown.stop_when(&fail);
  Box c = around(root, 0.25);
  CHECK_THROWS_AS(thrown.contract(c), std::runtime_error);
  thrown.stop_when(nullptr);
  CHECK(thrown.live_operations() == thrown.operations());
}

namespace {

// Random sparse terms of degree up to 4 in n of `variables` unknowns (some left unused), some
// cancelling to nothing.
Polynomial random_polynomial(int variables, std::mt19937& rng) {
  std::uniform_int_distribution<int> terms(0, 6), var(0, variables - 1), exponent(1, 4), coef(-3, 3);
  Polynomial p;
  const int count = terms(rng);
  for (int t = 0; t < count; ++t) {
    Polynomial m = Polynomial::constant(Interval(coef(rng) / 2.0));
    for (int k = var(rng) % 3; k > 0; --k) {
      const int v = var(rng) % std::max(1, variables - 2);
      for (int e = exponent(rng); e > 0; --e) m = m * Polynomial::variable(v);
    }
    p += m;
  }
  return p;
}

}  // namespace

TEST_CASE("the counts read from a system's shape are those of the contractors built from it", "[operations]") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 9;
    std::vector<Polynomial> f;
    for (int i = 0; i < 1 + (trial * 7) % 11; ++i) f.push_back(random_polynomial(n, rng));
    std::vector<model::Inequality> g;
    if (trial % 3 == 0) g.push_back({random_polynomial(n, rng), false, "g", {}});
    std::vector<model::Link> links;
    if (n >= 2 && trial % 4 == 0) links.push_back({model::Elementary::exp, n - 1, 0, "exp"});
    INFO("trial " << trial);
    const prune::Hc4 hc4(f, Arith::verified, g, links);
    CHECK(prune::Hc4::call_operations_of(f, g, links.size()) == hc4.call_operations());
    const model::CompiledSystem system(f, links, n);
    const auto shape = model::CompiledSystem::shape_of(f, links, n);
    CHECK(shape.value_operations == system.value_operations());
    CHECK(shape.jacobian_operations == system.jacobian_operations());
    CHECK(shape.rows == system.rows());
    CHECK(shape.cols == system.cols());
    CHECK(shape.nonzeros == system.nonzeros());
    const prune::IntervalNewton newton(f, n, Arith::verified, links);
    CHECK(prune::IntervalNewton::step_operations_of(f, n, links) == newton.step_operations());
  }
  CHECK_THROWS_AS(model::CompiledSystem::shape_of({Polynomial::variable(3)}, {}, 2), std::invalid_argument);
}
