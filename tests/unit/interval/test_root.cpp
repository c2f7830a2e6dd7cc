// root::nth_root against MPFR at 256 bits: each end bounds the true root on the right side
// and lies within 8 ulps of it, for odd and even powers, signs, and tiny to huge ends.
#include "interval/root.hpp"

#include <catch2/catch.hpp>

#include <mpfr.h>

#include <cmath>
#include <random>

using namespace linkbox;

namespace {

// The real e-th root of x at 256 bits compared with d: -1, 0, +1 as root < d, ==, >.
int root_vs(double x, int e, double d) {
  mpfr_t a;
  mpfr_init2(a, 256);
  mpfr_set_d(a, x, MPFR_RNDN);
  mpfr_rootn_ui(a, a, static_cast<unsigned long>(e), MPFR_RNDN);
  const int c = -mpfr_cmp_d(a, d);  // mpfr_cmp_d(a, d) > 0: root > d
  mpfr_clear(a);
  return c < 0 ? 1 : c > 0 ? -1 : 0;
}

// d moved k ulps towards `to`.
double step(double d, int k, double to) {
  for (int i = 0; i < k; ++i) d = std::nextafter(d, to);
  return d;
}

FastInterval root_of(double lo, double hi, int e) {
  RoundingGuard guard;
  return root::nth_root(FastInterval(lo, hi), e);
}

// r encloses the roots of [lo, hi], and (`tight`) its ends lie within 8 ulps of them.
void check(double lo, double hi, int e, bool tight = true) {
  const FastInterval r = root_of(lo, hi, e);
  INFO("e = " << e << ", [" << lo << ", " << hi << "] -> [" << r.lower() << ", " << r.upper() << "]");
  REQUIRE(root_vs(lo, e, r.lower()) >= 0);                   // r.lower() <= root(lo)
  REQUIRE(root_vs(hi, e, r.upper()) <= 0);                   // root(hi) <= r.upper()
  if (!tight) return;
  REQUIRE(root_vs(lo, e, step(r.lower(), 8, kInf)) <= 0);   // root(lo) <= r.lower() + 8 ulps
  REQUIRE(root_vs(hi, e, step(r.upper(), 8, -kInf)) >= 0);  // r.upper() - 8 ulps <= root(hi)
}

}  // namespace

TEST_CASE("nth_root encloses the real roots within 8 ulps", "[interval]") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  int checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int e = 2 + trial % 6;
    // Magnitudes from 1e-300 to 1e300; odd powers take both signs.
    const double a = std::pow(10.0, (unit(rng) - 0.5) * 600), w = std::pow(10.0, -16 * unit(rng));
    double lo = a, hi = a * (1 + w);
    if (e % 2 == 1 && trial % 3 == 0) lo = -a, hi = -a + a * w;
    if (e % 2 == 1 && trial % 3 == 1) lo = -a;
    check(lo, hi, e);
    ++checked;
  }
  CHECK(checked == 3000);
}

TEST_CASE("nth_root at zero, subnormals and exact powers", "[interval]") {
  for (int e = 2; e <= 7; ++e) {
    check(0.0, 0.0, e);
    check(0.0, 4.9e-324, e, false);  // the power of a root underflows: Boost's looser answer
    check(0.0, 1.0, e);
    check(std::pow(3.0, e), std::pow(3.0, e), e);
    if (e % 2 == 1) check(-8.0, 27.0, e);
  }
  const FastInterval r = root_of(27.0, 27.0, 3);
  CHECK(r.lower() == 3.0);
  CHECK(r.upper() == 3.0);
}
