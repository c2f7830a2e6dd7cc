// Proves outward rounding of Interval at the project's flags (-O2 -frounding-math
// -ffp-contract=off, set by CMake for this file too): every enclosure below is checked against
// exact rationals (GMP) or directed-rounding MPFR at 128/256 bits, never against doubles.
// Operands go through `opaque` so the compiler cannot fold the arithmetic at compile time
// (the -O3 failure in lib/README.md was exactly such a fold); a second copy uses literals.
#include "interval/box.hpp"
#include "interval/interval.hpp"
#include "interval/rigorous.hpp"

#include <catch2/catch.hpp>

#include <gmp.h>
#include <mpfr.h>

#include <cfenv>
#include <cmath>
#include <random>

#ifdef __FAST_MATH__
#error "interval tests must not be built with -ffast-math"
#endif

using namespace linkbox;

namespace {

template <class T>
T opaque(T v) {
  volatile T x = v;
  return x;
}

// Exact rational, from a double or n/d.
struct Rational {
  mpq_t v;
  explicit Rational(double d) {
    mpq_init(v);
    mpq_set_d(v, d);
  }
  Rational(long n, unsigned long d) {
    mpq_init(v);
    mpq_set_si(v, n, d);
    mpq_canonicalize(v);
  }
  ~Rational() { mpq_clear(v); }
  Rational(const Rational&) = delete;
  Rational& operator=(const Rational&) = delete;
};

// lo <= n/d <= hi, exactly.
bool contains_rational(const Interval& x, long n, unsigned long d) {
  Rational q(n, d), lo(x.lower()), hi(x.upper());
  return mpq_cmp(lo.v, q.v) <= 0 && mpq_cmp(q.v, hi.v) <= 0;
}

// MPFR number at a given precision.
struct Big {
  mpfr_t v;
  explicit Big(mpfr_prec_t prec = 256) { mpfr_init2(v, prec); }
  ~Big() { mpfr_clear(v); }
  Big(const Big&) = delete;
  Big& operator=(const Big&) = delete;
};

// x contains every real in [lo, hi] (lo, hi: MPFR lower/upper bounds of the true value).
bool encloses(const Interval& x, const Big& lo, const Big& hi) {
  return mpfr_cmp_d(lo.v, x.lower()) >= 0 && mpfr_cmp_d(hi.v, x.upper()) <= 0;
}

// Number of doubles strictly between a and b, capped: ulps(a, b) <= n  <=>  b within n steps.
bool within_ulps(double a, double b, int n) {
  for (int i = 0; i < n && a < b; ++i) a = std::nextafter(a, kInf);
  return a >= b;
}

// Checks that `r` encloses x*y for all corners, exactly, and is at most one ulp wider than
// the nearest-rounded extreme corner products on each side.
void check_product(const Interval& x, const Interval& y, const Interval& r) {
  Big corner(128), lo(128), hi(128);  // 53 x 53 bits: every product is exact at 128 bits
  bool first = true;
  for (double a : {x.lower(), x.upper()})
    for (double b : {y.lower(), y.upper()}) {
      mpfr_set_d(corner.v, a, MPFR_RNDN);
      mpfr_mul_d(corner.v, corner.v, b, MPFR_RNDN);
      if (first || mpfr_cmp(corner.v, lo.v) < 0) mpfr_set(lo.v, corner.v, MPFR_RNDN);
      if (first || mpfr_cmp(corner.v, hi.v) > 0) mpfr_set(hi.v, corner.v, MPFR_RNDN);
      first = false;
    }
  INFO("x = [" << x.lower() << ", " << x.upper() << "], y = [" << y.lower() << ", " << y.upper() << "]");
  REQUIRE(encloses(r, lo, hi));
  CHECK(within_ulps(r.lower(), mpfr_get_d(lo.v, MPFR_RNDN), 1));
  CHECK(within_ulps(mpfr_get_d(hi.v, MPFR_RNDN), r.upper(), 1));
}

// A random interval of the given sign class: -1 negative, 0 straddling zero, +1 positive.
Interval random_interval(std::mt19937_64& rng, int sign) {
  std::uniform_real_distribution<double> mantissa(0.1, 10.0);
  std::uniform_int_distribution<int> exponent(-30, 30);
  auto magnitude = [&] { return std::ldexp(mantissa(rng), exponent(rng)); };
  double a = magnitude(), b = magnitude();
  if (a > b) std::swap(a, b);
  if (sign > 0) return Interval(a, b);
  if (sign < 0) return Interval(-b, -a);
  return Interval(-a, b);
}

}  // namespace

TEST_CASE("interval: compiled without fast-math, round-to-nearest restored", "[interval]") {
  CHECK(std::fegetround() == FE_TONEAREST);
  const Interval third = Interval(opaque(1.0)) / Interval(opaque(3.0));
  CHECK(third.lower() < third.upper());
  CHECK(std::fegetround() == FE_TONEAREST);  // protected operations restore the mode
  {
    RoundingGuard guard;
    CHECK(std::fegetround() != FE_TONEAREST);
  }
  CHECK(std::fegetround() == FE_TONEAREST);
}

TEST_CASE("interval: 1/3 has non-zero width and contains the true third", "[interval]") {
  for (const Interval& third : {Interval(opaque(1.0)) / Interval(opaque(3.0)), Interval(1.0) / Interval(3.0)}) {
    CHECK(third.lower() < third.upper());
    CHECK(std::nextafter(third.lower(), kInf) == third.upper());  // tight: one ulp
    CHECK(contains_rational(third, 1, 3));                        // 3 lo < 1 < 3 hi, exactly
  }
  const Interval minus_third = Interval(opaque(-1.0)) / Interval(opaque(3.0));
  CHECK(contains_rational(minus_third, -1, 3));
  CHECK(minus_third.lower() < minus_third.upper());
}

TEST_CASE("interval: ten sums of the decimal 0.1 contain 1", "[interval]") {
  const Interval tenth = rigorous::decimal("0.1");
  CHECK(contains_rational(tenth, 1, 10));
  Interval sum(0.0);
  double naive = 0;
  for (int i = 0; i < 10; ++i) {
    sum += tenth;
    naive += opaque(0.1);
  }
  CHECK(naive != 1.0);  // why enclosures matter: the double sum misses 1
  CHECK(contains(sum, 1.0));
  CHECK(width_up(sum) < 1e-15);
}

TEST_CASE("interval: products of every sign combination enclose the corner products", "[interval]") {
  std::mt19937_64 rng(20240607);
  for (int sx : {-1, 0, 1})
    for (int sy : {-1, 0, 1})
      for (int k = 0; k < 200; ++k) {
        const Interval x = random_interval(rng, sx), y = random_interval(rng, sy);
        check_product(x, y, x * y);
      }
  // Zero endpoints and points, where sign-case code paths branch.
  const double v[] = {-3.3, -0.1, 0.0, 0.1, 7.7};
  for (double a : v)
    for (double b : v)
      for (double c : v)
        for (double d : v)
          if (a <= b && c <= d) check_product(Interval(a, b), Interval(c, d), Interval(a, b) * Interval(c, d));
}

// What linkbox relies on when a divisor may contain zero: the result still contains every
// quotient x/y with y != 0 in the divisor (whole line, or a half-line when 0 is an endpoint).
// The expression parser never divides by such intervals; it reports an error instead.
TEST_CASE("interval: division by intervals containing zero is sound (Boost's convention)", "[interval]") {
  const Interval x(1.0, 2.0);
  const Interval interior = x / Interval(-1.0, 1.0);
  CHECK(interior.lower() == -kInf);
  CHECK(interior.upper() == kInf);

  const Interval right = x / Interval(0.0, 3.0);  // [1/3, +inf)
  CHECK(right.lower() <= 1.0 / 3.0);
  CHECK(right.upper() == kInf);
  CHECK(contains_rational(Interval(right.lower(), 1.0), 1, 3));

  const Interval left = x / Interval(-3.0, 0.0);  // (-inf, -1/3]
  CHECK(left.lower() == -kInf);
  CHECK(contains_rational(Interval(-1.0, left.upper()), -1, 3));

  const Interval straddling = Interval(-1.0, 1.0) / Interval(0.0, 1.0);
  CHECK(straddling.lower() == -kInf);
  CHECK(straddling.upper() == kInf);

  // Degenerate cases: 0 / y is 0 (0/0 ignored); x / [0,0] is empty (NaN bounds here).
  const Interval zero = Interval(0.0) / Interval(-1.0, 1.0);
  CHECK((zero.lower() == 0 && zero.upper() == 0));
  CHECK(boost::numeric::empty(x / Interval(0.0)));
}

TEST_CASE("interval: sqrt encloses the true root, also near zero", "[interval]") {
  auto check_sqrt = [](double v) {
    const Interval r = boost::numeric::sqrt(Interval(opaque(v)));
    Big lo2(128), hi2(128);  // squares of doubles are exact at 128 bits
    mpfr_set_d(lo2.v, r.lower(), MPFR_RNDN);
    mpfr_sqr(lo2.v, lo2.v, MPFR_RNDN);
    mpfr_set_d(hi2.v, r.upper(), MPFR_RNDN);
    mpfr_sqr(hi2.v, hi2.v, MPFR_RNDN);
    INFO("sqrt(" << v << ") = [" << r.lower() << ", " << r.upper() << "]");
    CHECK(mpfr_cmp_d(lo2.v, v) <= 0);
    CHECK(mpfr_cmp_d(hi2.v, v) >= 0);
    CHECK(within_ulps(r.lower(), r.upper(), 1));
  };
  for (double v : {2.0, 3.0, 0.5, 1e-300, 4.9406564584124654e-324, 2.2250738585072014e-308, 1e300})
    check_sqrt(v);

  const Interval root2 = boost::numeric::sqrt(Interval(2.0));
  CHECK(root2.lower() < root2.upper());  // sqrt(2) is irrational: never a point
  // Boost clips a negative lower end to 0; linkbox code uses rigorous::sqrt, which throws.
  const Interval clipped = boost::numeric::sqrt(Interval(-1.0, 4.0));
  CHECK((clipped.lower() == 0 && clipped.upper() == 2));
  const Interval near_zero = boost::numeric::sqrt(Interval(0.0, opaque(1e-300)));
  CHECK(near_zero.lower() == 0);
  CHECK(near_zero.upper() * near_zero.upper() >= 1e-300);
}

TEST_CASE("interval: FastInterval inside a RoundingGuard gives the same enclosures", "[interval]") {
  std::mt19937_64 rng(7);
  std::vector<Interval> xs, ys;
  for (int k = 0; k < 100; ++k) {
    xs.push_back(random_interval(rng, k % 3 - 1));
    ys.push_back(random_interval(rng, (k / 3) % 3 - 1));
  }
  const Interval tenth = rigorous::decimal("0.1");
  // Everything the guard's scope computes is stored; comparisons happen after the mode is restored.
  std::vector<double> fast, slow;
  auto record = [](std::vector<double>& out, double lo, double hi) {
    out.push_back(lo);
    out.push_back(hi);
  };
  for (size_t k = 0; k < xs.size(); ++k) {
    const Interval &x = xs[k], &y = ys[k];
    record(slow, (x * y).lower(), (x * y).upper());
    record(slow, (x + y).lower(), (x + y).upper());
    record(slow, (x - y).lower(), (x - y).upper());
    if (!boost::numeric::zero_in(y)) record(slow, (x / y).lower(), (x / y).upper());
  }
  Interval third = Interval(opaque(1.0)) / Interval(opaque(3.0)), sum(0.0),
           root = boost::numeric::sqrt(Interval(2.0));
  for (int i = 0; i < 10; ++i) sum += tenth;
  record(slow, third.lower(), third.upper());
  record(slow, sum.lower(), sum.upper());
  record(slow, root.lower(), root.upper());
  {
    RoundingGuard guard;
    for (size_t k = 0; k < xs.size(); ++k) {
      const FastInterval x(xs[k].lower(), xs[k].upper()), y(ys[k].lower(), ys[k].upper());
      record(fast, (x * y).lower(), (x * y).upper());
      record(fast, (x + y).lower(), (x + y).upper());
      record(fast, (x - y).lower(), (x - y).upper());
      if (!boost::numeric::zero_in(y)) record(fast, (x / y).lower(), (x / y).upper());
    }
    const FastInterval t = FastInterval(opaque(1.0)) / FastInterval(opaque(3.0));
    FastInterval s(0.0);
    for (int i = 0; i < 10; ++i) s += FastInterval(tenth.lower(), tenth.upper());
    const FastInterval r = boost::numeric::sqrt(FastInterval(2.0));
    record(fast, t.lower(), t.upper());
    record(fast, s.lower(), s.upper());
    record(fast, r.lower(), r.upper());
  }
  REQUIRE(fast.size() == slow.size());
  for (size_t i = 0; i < fast.size(); ++i) {
    INFO("value " << i);
    CHECK(fast[i] == slow[i]);
  }
}

TEST_CASE("interval: NearestScope's and centre_box's midpoints are median's, in any mode", "[interval]") {
  std::mt19937_64 rng(11);
  std::vector<Interval> xs;
  for (int k = 0; k < 100; ++k) xs.push_back(random_interval(rng, k % 3 - 1));
  xs.push_back(Interval(opaque(1.0), opaque(1.0) + 0x1p-52));  // the sum's last bit is rounded
  std::vector<double> reference, scoped;
  for (const Interval& x : xs) reference.push_back(median(x));
  int inside = 0;
  {
    RoundingGuard guard;  // upward, as where the map's Krawczyk steps take their midpoints
    {
      const NearestScope nearest;
      for (const Interval& x : xs) scoped.push_back(nearest.median(x));
      inside = std::fegetround();
    }
    CHECK(std::fegetround() == FE_UPWARD);
  }
  CHECK(inside == FE_TONEAREST);
  CHECK(std::fegetround() == FE_TONEAREST);
  REQUIRE(scoped.size() == reference.size());
  for (size_t k = 0; k < xs.size(); ++k) {
    INFO("interval " << k);
    CHECK(scoped[k] == reference[k]);
  }
  Box centred;
  {
    RoundingGuard guard;
    centred = centre_box(Box(xs.begin(), xs.end()));
  }
  for (size_t k = 0; k < xs.size(); ++k) {
    INFO("side " << k);
    CHECK(centred[k].lower() == reference[k]);
    CHECK(centred[k].upper() == reference[k]);
  }
  const NearestScope nearest;
  CHECK(std::isnan(nearest.median(Interval(opaque(2.0), opaque(1.0)))));  // empty, as median says
}

TEST_CASE("interval: excludes_zero proves nothing from NaN bounds", "[interval]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(excludes_zero(Interval(1.0, 2.0)));
  CHECK(excludes_zero(FastInterval(-2.0, -1.0)));
  CHECK_FALSE(excludes_zero(Interval(-1.0, 0.0)));
  CHECK_FALSE(excludes_zero(FastInterval(nan, nan)));
  CHECK_FALSE(excludes_zero(FastInterval(nan, 1.0)));
}

TEST_CASE("rigorous: decimal literals are tight enclosures of the decimal", "[interval][rigorous]") {
  const Interval x = rigorous::decimal("0.0175");
  CHECK(contains_rational(x, 175, 10000));
  CHECK(x.lower() < x.upper());  // 0.0175 is not a double
  CHECK(within_ulps(x.lower(), x.upper(), 2));
  CHECK_FALSE(contains_rational(Interval(0.0175), 175, 10000));  // the double alone misses it

  CHECK(contains_rational(rigorous::decimal("-0.7448995469549714"), -7448995469549714L, 10000000000000000UL));
  CHECK(contains_rational(rigorous::decimal("1e-7"), 1, 10000000));
  const Interval half = rigorous::decimal("0.5");
  CHECK((half.lower() == 0.5 && half.upper() == 0.5));  // exact decimals stay points
  CHECK_THROWS_AS(rigorous::decimal("0.5x"), std::invalid_argument);
}

TEST_CASE("rigorous: pi, sin/cos(pi/3) and acos(-1/3) contain the true values", "[interval][rigorous]") {
  Big lo, hi;  // 256-bit directed bounds of each true value
  mpfr_const_pi(lo.v, MPFR_RNDD);
  mpfr_const_pi(hi.v, MPFR_RNDU);
  const Interval pi = rigorous::pi();
  CHECK(encloses(pi, lo, hi));
  CHECK(within_ulps(pi.lower(), pi.upper(), 1));

  const Interval third_pi = pi / Interval(3.0);
  const Interval c = rigorous::cos(third_pi), s = rigorous::sin(third_pi);
  CHECK(contains(c, 0.5));
  mpfr_sqrt_ui(lo.v, 3, MPFR_RNDD);
  mpfr_div_ui(lo.v, lo.v, 2, MPFR_RNDD);
  mpfr_sqrt_ui(hi.v, 3, MPFR_RNDU);
  mpfr_div_ui(hi.v, hi.v, 2, MPFR_RNDU);
  CHECK(encloses(s, lo, hi));
  CHECK(width_up(s) < 1e-15);
  CHECK(width_up(c) < 1e-15);

  // acos is decreasing: acos(-1/3) lies in [acos(u), acos(d)] for d <= -1/3 <= u.
  Big d, u;
  mpfr_set_si(d.v, -1, MPFR_RNDN);
  mpfr_div_ui(d.v, d.v, 3, MPFR_RNDD);
  mpfr_set_si(u.v, -1, MPFR_RNDN);
  mpfr_div_ui(u.v, u.v, 3, MPFR_RNDU);
  mpfr_acos(lo.v, u.v, MPFR_RNDD);
  mpfr_acos(hi.v, d.v, MPFR_RNDU);
  const Interval a = rigorous::acos(Interval(-1.0) / Interval(3.0));
  CHECK(encloses(a, lo, hi));
  CHECK(width_up(a) < 1e-15);
}
