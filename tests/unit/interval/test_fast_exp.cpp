// fast_exp::exp and log against MPFR at 256 bits (points inside each interval and its ends)
// and against MPFI's enclosure (tight within a few ulps, relative).
#include "interval/fast_exp.hpp"
#include "interval/rigorous.hpp"

#include <catch2/catch.hpp>

#include <mpfr.h>

#include <cmath>
#include <limits>
#include <random>

using namespace linkbox;

namespace {

using Mpfr = int (*)(mpfr_ptr, mpfr_srcptr, mpfr_rnd_t);

// Whether f(x) at 256 bits lies in r.
bool holds_at(Mpfr f, double x, const FastInterval& r) {
  mpfr_t a, v;
  mpfr_inits2(256, a, v, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_d(a, x, MPFR_RNDN);
  f(v, a, MPFR_RNDN);
  const bool ok = mpfr_cmp_d(v, r.lower()) >= 0 && mpfr_cmp_d(v, r.upper()) <= 0;
  mpfr_clears(a, v, static_cast<mpfr_ptr>(nullptr));
  return ok;
}

double ulp(double x) { return std::nextafter(std::fabs(x), kInf) - std::fabs(x); }

// Holds MPFI's enclosure but for one ulp, and exceeds it by at most `ulps` ulps at each end.
bool near_mpfi(const FastInterval& ours, const Interval& mpfi, double ulps) {
  const double lo = mpfi.lower(), hi = mpfi.upper();
  return ours.lower() <= lo + ulp(lo) && hi - ulp(hi) <= ours.upper() && lo - ulps * ulp(lo) <= ours.lower() &&
         ours.upper() <= hi + ulps * ulp(hi);
}

FastInterval fast(bool (*f)(const FastInterval&, FastInterval&), double lo, double hi) {
  RoundingGuard guard;
  FastInterval r;
  REQUIRE(f(FastInterval(lo, hi), r));
  return r;
}

}  // namespace

TEST_CASE("fast exp and log enclose the range and stay within 8 ulps of MPFI's", "[interval]") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  const double widths[] = {0, 1e-15, 1e-9, 1e-4, 0.01, 0.3, 2.0, 30.0};
  for (int trial = 0; trial < 800; ++trial) {
    const double w = widths[trial % 8];
    // exp: ends across [-700, 700], half of them near 0 and near multiples of ln 2.
    double c = (unit(rng) - 0.5) * 1300;
    if (trial % 2) c = std::round((unit(rng) - 0.5) * 40) * 0.6931471805599453 + (unit(rng) - 0.5) * 1e-9;
    const double lo = c - w / 2, hi = c + w / 2;
    const FastInterval e = fast(fast_exp::exp, lo, hi);
    INFO("exp [" << lo << ", " << hi << "]");
    REQUIRE(holds_at(mpfr_exp, lo, e));
    REQUIRE(holds_at(mpfr_exp, hi, e));
    for (int k = 0; k < 4; ++k) REQUIRE(holds_at(mpfr_exp, lo + unit(rng) * (hi - lo), e));
    REQUIRE(near_mpfi(e, rigorous::exp(Interval(lo, hi)), 8));
    // log: ends from subnormal to 1e300, half of them within 1e-6 of 1 (where log is small).
    double x = std::pow(10.0, (unit(rng) - 0.5) * 600);
    if (trial % 2) x = 1 + (unit(rng) - 0.5) * 1e-6;
    const double l = x, h = x * (1 + w);
    const FastInterval g = fast(fast_exp::log, l, h);
    INFO("log [" << l << ", " << h << "]");
    REQUIRE(holds_at(mpfr_log, l, g));
    REQUIRE(holds_at(mpfr_log, h, g));
    for (int k = 0; k < 4; ++k) REQUIRE(holds_at(mpfr_log, l + unit(rng) * (h - l), g));
    REQUIRE(near_mpfi(g, rigorous::log(Interval(l, h)), 8));
  }
}

TEST_CASE("fast exp and log answer exactly where exact, and decline outside their range", "[interval]") {
  const FastInterval one = fast(fast_exp::exp, 0, 0);
  CHECK(one.lower() <= 1);
  CHECK(one.upper() >= 1);
  CHECK(one.upper() - one.lower() <= 4e-16);
  const FastInterval zero = fast(fast_exp::log, 1, 1);
  CHECK(zero.lower() <= 0);
  CHECK(zero.upper() >= 0);
  CHECK(zero.upper() - zero.lower() <= 1e-300);
  CHECK(holds_at(mpfr_log, 4.9e-324, fast(fast_exp::log, 4.9e-324, 1.0)));
  RoundingGuard guard;
  FastInterval r(-1.0, 1.0);
  CHECK_FALSE(fast_exp::exp(FastInterval(-1.0, 701.0), r));
  CHECK_FALSE(fast_exp::exp(FastInterval(-1e8, -720.0), r));  // a subnormal upper end: MPFI's
  CHECK_FALSE(fast_exp::exp(FastInterval(-1e8, kInf), r));
  CHECK_FALSE(fast_exp::log(FastInterval(0.0, 1.0), r));
  CHECK_FALSE(fast_exp::log(FastInterval(1.0, kInf), r));
  CHECK(r.lower() == -1.0);  // untouched where declined
  CHECK(r.upper() == 1.0);
}

TEST_CASE("fast exp bounds ends far below 0 by 0 and the least subnormal", "[interval]") {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const double lo = -700 - std::pow(10.0, unit(rng) * 8), hi = (unit(rng) - 0.5) * 1400;
    if (hi < lo || (hi < -700 && hi >= -746)) continue;
    const FastInterval e = fast(fast_exp::exp, lo, hi);
    INFO("exp [" << lo << ", " << hi << "]");
    REQUIRE(e.lower() == 0);
    REQUIRE(holds_at(mpfr_exp, lo, e));
    REQUIRE(holds_at(mpfr_exp, hi, e));
    for (int k = 0; k < 4; ++k) REQUIRE(holds_at(mpfr_exp, lo + unit(rng) * (hi - lo), e));
    if (hi >= -700) REQUIRE(near_mpfi(FastInterval(0, e.upper()), rigorous::exp(Interval(-kInf, hi)), 8));
  }
  const FastInterval whole = fast(fast_exp::exp, -kInf, 0.0);
  CHECK(whole.lower() == 0);
  CHECK(whole.upper() >= 1);
  const FastInterval tiny = fast(fast_exp::exp, -1e8, -800.0);
  CHECK(tiny.lower() == 0);
  CHECK(tiny.upper() == std::numeric_limits<double>::denorm_min());
  mpfr_t a;  // exp(-746) < 2^-1075, half the least subnormal
  mpfr_init2(a, 256);
  mpfr_set_d(a, -746.0, MPFR_RNDN);
  mpfr_exp(a, a, MPFR_RNDU);
  CHECK(mpfr_cmp_ui_2exp(a, 1, -1075) < 0);
  mpfr_clear(a);
}
