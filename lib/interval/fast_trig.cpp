#include "interval/fast_trig.hpp"

#include "interval/rigorous.hpp"

#include <array>
#include <cmath>

namespace linkbox::fast_trig {

namespace {

using F = FastInterval;

// Taylor terms: with |r| <= pi/4 + 1e-9 the remainder is below 2.1e-18 for cos (whose values
// there are at least 0.7: 0.02 ulp) and |r| times 1.1e-19 for sin.
constexpr int kTerms = 9;
// Beyond this the reduction's error (k times the width of pi/2's enclosure) grows: MPFI.
constexpr double kLargest = 1 << 20;
// An interval this wide holds a whole period (2 pi < 6.3, whatever the subtraction's
// rounding), so both extrema of sin and of cos.
constexpr double kFullTurn = 6.3;

struct Constants {
  std::array<F, 2 * kTerms + 2> inverse_factorial;  // 1/k!, k <= 2 kTerms + 1
  F half_pi;
};

const Constants& constants() {
  static const Constants c = [] {
    RoundingGuard guard;
    Constants k;
    k.inverse_factorial[0] = F(1.0);
    for (int i = 1; i <= 2 * kTerms + 1; ++i) k.inverse_factorial[i] = k.inverse_factorial[i - 1] / F(double(i));
    const Interval pi = rigorous::pi();
    k.half_pi = F(pi.lower(), pi.upper()) / 2.0;
    return k;
  }();
  return c;
}

// |r|^n / n! times [-1, 1]: the Lagrange remainder after the terms below degree n.
F remainder(const F& r, int n) {
  const double m = std::max(std::fabs(r.lower()), std::fabs(r.upper()));
  const F bound = boost::numeric::pow(F(m), n) * constants().inverse_factorial[n];
  return F(-bound.upper(), bound.upper());
}

// sin and cos of r (|r| small) by their Taylor polynomials in Horner form.
SinCos taylor(const F& r) {
  const auto& f = constants().inverse_factorial;
  const F r2 = boost::numeric::square(r);
  F s(0.0), c(0.0);
  for (int i = kTerms - 1; i >= 0; --i) {
    const double sign = i % 2 == 0 ? 1.0 : -1.0;
    s = s * r2 + sign * f[2 * i + 1];
    c = c * r2 + sign * f[2 * i];
  }
  return {s * r + remainder(r, 2 * kTerms + 1), c + remainder(r, 2 * kTerms)};
}

// Quarter turns in x, as a float choice: the reduction below is exact in intervals for any k.
long quarter_turns(double x) { return std::lround(x / 1.5707963267948966); }

SinCos at(double x) {
  const long k = quarter_turns(x);
  const SinCos t = taylor(F(x) - double(k) * constants().half_pi);
  // sin(r + k pi/2), cos(r + k pi/2) by the quarter turn k mod 4.
  switch (((k % 4) + 4) % 4) {
    case 0: return t;
    case 1: return {t.cos, -t.sin};
    case 2: return {-t.sin, -t.cos};
    default: return {-t.cos, t.sin};
  }
}

F join(const F& a, const F& b) { return F(std::min(a.lower(), b.lower()), std::max(a.upper(), b.upper())); }

F within_one(const F& x) { return F(std::max(x.lower(), -1.0), std::min(x.upper(), 1.0)); }

SinCos by_mpfi(const F& x) {
  const Interval y(x.lower(), x.upper());
  const Interval s = rigorous::sin(y), c = rigorous::cos(y);
  return {F(s.lower(), s.upper()), F(c.lower(), c.upper())};
}

}  // namespace

SinCos sin_cos(const FastInterval& x) {
  const double lo = x.lower(), hi = x.upper();
  if (hi - lo >= kFullTurn) return {F(-1.0, 1.0), F(-1.0, 1.0)};  // infinite ends too
  if (!(std::fabs(lo) <= kLargest && std::fabs(hi) <= kLargest)) return by_mpfi(x);
  const SinCos a = at(lo), b = lo == hi ? a : at(hi);
  SinCos r{join(a.sin, b.sin), join(a.cos, b.cos)};
  // The extrema lie at the multiples m pi/2; one the interval may hold (its enclosure meets
  // [lo, hi]) adds its value: m = 0 mod 4 cos = 1, 1 sin = 1, 2 cos = -1, 3 sin = -1.
  const F& h = constants().half_pi;
  for (long m = quarter_turns(lo) - 1; m <= quarter_turns(hi) + 1; ++m) {
    const F point = double(m) * h;
    if (point.upper() < lo || hi < point.lower()) continue;
    switch (((m % 4) + 4) % 4) {
      case 0: r.cos = join(r.cos, F(1.0)); break;
      case 1: r.sin = join(r.sin, F(1.0)); break;
      case 2: r.cos = join(r.cos, F(-1.0)); break;
      default: r.sin = join(r.sin, F(-1.0)); break;
    }
  }
  return {within_one(r.sin), within_one(r.cos)};
}

}  // namespace linkbox::fast_trig
