#pragma once
// sin and cos of an interval in double arithmetic: the ends are reduced by an enclosure of
// pi/2 and evaluated by Taylor polynomials whose remainder is bounded (Lagrange form), all
// outward rounded, and the extrema at the multiples of pi/2 that the interval may hold are
// added. An enclosure of the range like rigorous::sin/cos (MPFI), a few ulps wider, without
// libm and without multi-precision, for hot loops. An interval wider than a period gives
// [-1, 1] at once; arguments far from 0 (or NaN) go to rigorous::.
#include "interval/interval.hpp"

namespace linkbox::fast_trig {

struct SinCos {
  FastInterval sin, cos;
};

// Requires a live RoundingGuard (FastInterval arithmetic).
SinCos sin_cos(const FastInterval& x);

}  // namespace linkbox::fast_trig
