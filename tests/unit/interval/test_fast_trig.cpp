// fast_trig::sin_cos against MPFR at 256 bits (points inside each interval and its ends) and
// against MPFI's range (extrema at the multiples of pi/2, tightness).
#include "interval/fast_trig.hpp"
#include "interval/rigorous.hpp"

#include <catch2/catch.hpp>

#include <mpfr.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

using namespace linkbox;

namespace {

// Whether sin and cos of the double x, at 256 bits, lie in s and c.
bool holds_at(double x, const FastInterval& s, const FastInterval& c) {
  mpfr_t a, v;
  mpfr_inits2(256, a, v, static_cast<mpfr_ptr>(nullptr));
  mpfr_set_d(a, x, MPFR_RNDN);
  mpfr_sin(v, a, MPFR_RNDN);
  bool ok = mpfr_cmp_d(v, s.lower()) >= 0 && mpfr_cmp_d(v, s.upper()) <= 0;
  mpfr_cos(v, a, MPFR_RNDN);
  ok = ok && mpfr_cmp_d(v, c.lower()) >= 0 && mpfr_cmp_d(v, c.upper()) <= 0;
  mpfr_clears(a, v, static_cast<mpfr_ptr>(nullptr));
  return ok;
}

fast_trig::SinCos fast(double lo, double hi) {
  RoundingGuard guard;
  return fast_trig::sin_cos(FastInterval(lo, hi));
}

// Within `slack` of MPFI's enclosure on both sides, and holding it but for one ulp.
bool near_mpfi(const FastInterval& ours, const Interval& mpfi, double slack) {
  const double lo = std::nextafter(mpfi.lower(), 1.0), hi = std::nextafter(mpfi.upper(), -1.0);
  return ours.lower() <= lo && hi <= ours.upper() && mpfi.lower() - slack <= ours.lower() &&
         ours.upper() <= mpfi.upper() + slack;
}

}  // namespace

TEST_CASE("fast sin and cos enclose the range and stay within 1e-14 of MPFI's", "[interval]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> centre(-30, 30), unit(0, 1);
  const double widths[] = {0, 1e-14, 1e-9, 1e-4, 0.01, 0.3, 1.7, 3.2, 6.5};
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // Half the intervals sit on a multiple of pi/2, where the extrema are.
    double c = centre(rng);
    if (trial % 2) c = std::round(c / 1.5707963267948966) * 1.5707963267948966 + (unit(rng) - 0.5) * 1e-12;
    const double w = widths[trial % 9];
    const double lo = c - w / 2, hi = c + w / 2;
    const auto r = fast(lo, hi);
    INFO("[" << lo << ", " << hi << "]");
    REQUIRE(holds_at(lo, r.sin, r.cos));
    REQUIRE(holds_at(hi, r.sin, r.cos));
    for (int k = 0; k < 8; ++k) REQUIRE(holds_at(lo + unit(rng) * (hi - lo), r.sin, r.cos));
    const Interval x(lo, hi);
    REQUIRE(near_mpfi(r.sin, rigorous::sin(x), 1e-14));
    REQUIRE(near_mpfi(r.cos, rigorous::cos(x), 1e-14));
    ++checked;
  }
  CHECK(checked == 400);
}

TEST_CASE("fast sin and cos of a point within a quarter turn are a few ulps wide", "[interval]") {
  // The reduction adds at most pi/2's enclosure (2.3e-16) here, so a wider result would come
  // from the Taylor remainder: too few terms.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> x(-2.3, 2.3);
  double widest = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const double at = x(rng);
    const auto r = fast(at, at);
    REQUIRE(holds_at(at, r.sin, r.cos));
    widest = std::max({widest, r.sin.upper() - r.sin.lower(), r.cos.upper() - r.cos.lower()});
  }
  INFO("widest " << widest);
  CHECK(widest < 1e-15);
}

TEST_CASE("fast sin and cos hand far, wide and point-like arguments to MPFI", "[interval]") {
  for (auto [lo, hi] : {std::pair{1e7, 1e7 + 1}, std::pair{-3.0, 9.0}, std::pair{0.0, 0.0}, std::pair{-1e-300, 1e-300}}) {
    const auto r = fast(lo, hi);
    const Interval x(lo, hi);
    CHECK(near_mpfi(r.sin, rigorous::sin(x), 1e-14));
    CHECK(near_mpfi(r.cos, rigorous::cos(x), 1e-14));
    CHECK(holds_at(lo, r.sin, r.cos));
    CHECK(holds_at(hi, r.sin, r.cos));
  }
}

TEST_CASE("fast sin and cos of an interval of a period or more are [-1, 1], and not before", "[interval]") {
  // Just under 2 pi some value is still missed: a shortcut taken too early would be wider than
  // MPFI's range there by far more than the slack.
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> centre(-50, 50);
  const double widths[] = {6.0, 6.2, 6.28, 6.2831, 6.3, 7.9, 8.1, 100, 1e5};
  for (int trial = 0; trial < 180; ++trial) {
    const double c = centre(rng), w = widths[trial % 9], lo = c - w / 2, hi = c + w / 2;
    const auto r = fast(lo, hi);
    INFO("[" << lo << ", " << hi << "]");
    const Interval x(lo, hi);
    REQUIRE(near_mpfi(r.sin, rigorous::sin(x), 1e-14));
    REQUIRE(near_mpfi(r.cos, rigorous::cos(x), 1e-14));
  }
  const double inf = std::numeric_limits<double>::infinity();
  for (auto [lo, hi] : {std::pair{-inf, 0.0}, std::pair{3.0, inf}, std::pair{-inf, inf}}) {
    const auto r = fast(lo, hi);
    CHECK((r.sin.lower() == -1 && r.sin.upper() == 1 && r.cos.lower() == -1 && r.cos.upper() == 1));
  }
}
