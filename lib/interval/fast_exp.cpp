#include "interval/fast_exp.hpp"

#include <mpfi.h>

#include <array>
#include <cmath>
#include <limits>

namespace linkbox::fast_exp {

namespace {

using F = FastInterval;

// exp's reduced argument stays within ln2/2 + 1e-12, where the remainder after kExpTerms terms,
// |r|^n / n! times e^|r| < 2, is below 1e-24 relative to exp(r) >= 0.7.
constexpr int kExpTerms = 18;
// log's series in s = (m - 1)/(m + 1), |s| <= 0.172: 2 (s + s^3/3 + ...), remainder below
// 2 |s|^(2n+1) / ((2n+1)(1 - s^2)) < 1e-24 |s| after kLogTerms terms.
constexpr int kLogTerms = 14;
constexpr double kLargest = 700;  // exp's ends beyond: MPFI (overflow and subnormal results)
constexpr double kUnderflow = -746;  // exp below: under half the least subnormal

struct Constants {
  std::array<F, kExpTerms + 1> inverse_factorial;  // 1/k!
  std::array<F, kLogTerms> inverse_odd;           // 1/(2k+1)
  double ln2_high = 0;  // ln 2 to 32 bits: k * ln2_high is exact for |k| < 2^20
  F ln2_low;            // ln 2 - ln2_high, enclosed
  F ln2;
};

// [lo, hi] of an MPFI value as doubles rounded outward.
F to_fast(mpfi_t v) { return F(mpfr_get_d(&v->left, MPFR_RNDD), mpfr_get_d(&v->right, MPFR_RNDU)); }

const Constants& constants() {
  static const Constants c = [] {
    Constants k;
    mpfi_t ln2, low;
    mpfi_init2(ln2, 256);
    mpfi_init2(low, 256);
    mpfi_const_log2(ln2);
    k.ln2_high = std::ldexp(std::floor(std::ldexp(0.6931471805599453, 32)), -32);
    mpfi_sub_d(low, ln2, k.ln2_high);
    k.ln2_low = to_fast(low);
    k.ln2 = to_fast(ln2);
    mpfi_clear(ln2);
    mpfi_clear(low);
    RoundingGuard guard;
    k.inverse_factorial[0] = F(1.0);
    for (int i = 1; i <= kExpTerms; ++i) k.inverse_factorial[i] = k.inverse_factorial[i - 1] / F(double(i));
    for (int i = 0; i < kLogTerms; ++i) k.inverse_odd[i] = F(1.0) / F(double(2 * i + 1));
    return k;
  }();
  return c;
}

// [-b, b] with b = m^n * c, m = max |r|: a remainder's enclosure.
F remainder(const F& r, int n, const F& c) {
  const double m = std::max(std::fabs(r.lower()), std::fabs(r.upper()));
  const double b = (boost::numeric::pow(F(m), n) * c).upper();
  return F(-b, b);
}

// exp of the double x, |x| <= kLargest: x = k ln2 + r, exp(x) = 2^k exp(r).
F exp_at(double x) {
  const Constants& c = constants();
  // floor, not nearbyint: nearbyint follows the rounding mode (upward here), which would let
  // |r| reach ln 2 instead of ln2/2.
  const double k = std::floor(x / 0.6931471805599453 + 0.5);
  const F r = (F(x) - F(k) * c.ln2_high) - k * c.ln2_low;
  F s(0.0);
  for (int i = kExpTerms - 1; i >= 0; --i) s = s * r + c.inverse_factorial[i];
  s += remainder(r, kExpTerms, c.inverse_factorial[kExpTerms] * 2.0);
  const int e = static_cast<int>(k);
  return F(std::ldexp(std::max(s.lower(), 0.0), e), std::ldexp(s.upper(), e));
}

// log of the double x > 0 (finite): x = m 2^e with m in [sqrt(1/2), sqrt(2)).
F log_at(double x) {
  const Constants& c = constants();
  int e = 0;
  double m = std::frexp(x, &e);  // m in [1/2, 1)
  if (m < 0.7071067811865476) m *= 2, --e;
  const F s = (F(m) - 1.0) / (F(m) + 1.0);
  const F s2 = boost::numeric::square(s);
  F t(0.0);
  for (int i = kLogTerms - 1; i >= 0; --i) t = t * s2 + c.inverse_odd[i];
  // The series' tail over 2s: s^(2n) / ((2n+1)(1 - s^2)), with 1 - s^2 >= 0.97.
  t += remainder(s, 2 * kLogTerms, c.inverse_odd[kLogTerms - 1] / 0.97);
  return 2.0 * s * t + double(e) * c.ln2;
}

bool finite(const FastInterval& x) { return std::isfinite(x.lower()) && std::isfinite(x.upper()); }

}  // namespace

bool exp(const FastInterval& x, FastInterval& out) {
  const double lo = x.lower(), hi = x.upper();
  if (!std::isfinite(hi) || hi > kLargest || (hi < -kLargest && hi >= kUnderflow) || std::isnan(lo)) return false;
  // exp > 0 bounds an end far below from under; exp(kUnderflow) < 2^-1076 from over.
  const double low = lo < -kLargest ? 0.0 : exp_at(lo).lower();
  const double high = hi < kUnderflow ? std::numeric_limits<double>::denorm_min() : exp_at(hi).upper();
  out = F(low, high);
  return true;
}

bool log(const FastInterval& x, FastInterval& out) {
  if (!finite(x) || !(x.lower() > 0)) return false;
  out = F(log_at(x.lower()).lower(), log_at(x.upper()).upper());
  return true;
}

}  // namespace linkbox::fast_exp
