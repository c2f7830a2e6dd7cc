#pragma once
// Doubles as scaled integers, for the exact simplex: a finite double is an odd integer times a
// power of two, so a row of doubles times a power of two is a row of integers, and values over
// one common power of two compare and combine without fractions.
#include <gmpxx.h>
#include <mpfr.h>

#include <algorithm>
#include <cmath>

namespace linkbox::prune::lp {

// v = mantissa * 2^exponent with an odd mantissa; 0 for v = 0. v must be finite.
struct Dyadic {
  long mantissa = 0;
  int exponent = 0;
};
inline Dyadic split(double v) {
  if (v == 0) return {};
  int e = 0;
  const double f = std::frexp(v, &e);  // v = f 2^e, 1/2 <= |f| < 1
  long m = static_cast<long>(std::ldexp(f, 53));  // exact: 53 significant bits
  e -= 53;
  while ((m & 1) == 0) m /= 2, ++e;
  return {m, e};
}

// out = v * 2^shift; requires shift + (the exponent of v's lowest bit) >= 0.
inline void set_scaled(mpz_class& out, double v, int shift) {
  const Dyadic d = split(v);
  out = d.mantissa;
  if (d.mantissa != 0) mpz_mul_2exp(out.get_mpz_t(), out.get_mpz_t(), static_cast<mp_bitcnt_t>(d.exponent + shift));
}

// out = v * 2^shift * z, the same as set_scaled then a product, but the product is taken on
// v's 53-bit mantissa before the shift (a product with the shifted number would multiply
// mostly zero limbs).
inline void set_scaled_times(mpz_class& out, double v, int shift, const mpz_class& z) {
  const Dyadic d = split(v);
  if (d.mantissa == 0) {
    out = 0;
    return;
  }
  mpz_mul_si(out.get_mpz_t(), z.get_mpz_t(), d.mantissa);
  mpz_mul_2exp(out.get_mpz_t(), out.get_mpz_t(), static_cast<mp_bitcnt_t>(d.exponent + shift));
}

// The exponent of v's lowest bit (v finite, non-zero), as a shift that makes v an integer.
inline int integer_shift(double v) { return v == 0 ? 0 : std::max(0, -split(v).exponent); }

// log2 |z| (z != 0), enough to rank sizes.
inline double log2_abs(const mpz_class& z) {
  long e = 0;
  const double d = mpz_get_d_2exp(&e, z.get_mpz_t());
  return std::log2(std::fabs(d)) + static_cast<double>(e);
}

// The largest double <= num / den (den > 0), correctly rounded by MPFR.
inline double round_down(const mpz_class& num, const mpz_class& den) {
  if (sgn(num) == 0) return 0;
  mpfr_t exact, result;
  mpfr_init2(exact, std::max<mpfr_prec_t>(53, static_cast<mpfr_prec_t>(mpz_sizeinbase(num.get_mpz_t(), 2))));
  mpfr_init2(result, 53);
  mpfr_set_z(exact, num.get_mpz_t(), MPFR_RNDN);  // exact at this precision
  mpfr_div_z(result, exact, den.get_mpz_t(), MPFR_RNDD);
  const double d = mpfr_get_d(result, MPFR_RNDD);
  mpfr_clear(exact);
  mpfr_clear(result);
  return d;
}

// a * 2^ea < b * 2^eb for non-negative integers.
inline bool less_scaled(const mpz_class& a, int ea, const mpz_class& b, int eb, mpz_class& t) {
  if (ea >= eb) {
    mpz_mul_2exp(t.get_mpz_t(), a.get_mpz_t(), static_cast<mp_bitcnt_t>(ea - eb));
    return t < b;
  }
  mpz_mul_2exp(t.get_mpz_t(), b.get_mpz_t(), static_cast<mp_bitcnt_t>(eb - ea));
  return a < t;
}

}  // namespace linkbox::prune::lp
