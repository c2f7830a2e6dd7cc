#pragma once
// Rigorous enclosures of constants and elementary functions, through MPFI (multi-precision
// interval arithmetic over MPFR). libm's sin/cos ignore the rounding mode, so nothing
// transcendental in linkbox goes through libm.
#include "interval/interval.hpp"

#include <string_view>

namespace linkbox::rigorous {

// Tight enclosure of a decimal literal such as "0.0175" or "1e-7" (the decimal value, not
// the nearest double). Throws std::invalid_argument when `text` is not a number.
Interval decimal(std::string_view text);

Interval pi();
Interval sin(const Interval& x);
Interval cos(const Interval& x);
Interval tan(const Interval& x);   // throws std::domain_error if x meets a pole
Interval asin(const Interval& x);  // throws std::domain_error outside [-1, 1]
Interval acos(const Interval& x);
Interval atan(const Interval& x);
// Angle of the points (x, y) of a box: encloses {atan2(y, x)} within [-pi, pi]. Across the
// cut, where atan2 jumps (x < 0 with y of both signs, or y exactly 0), it is all of [-pi, pi].
Interval atan2(const Interval& y, const Interval& x);
Interval sqrt(const Interval& x);  // throws std::domain_error for negative x
Interval exp(const Interval& x);
Interval log(const Interval& x);   // throws std::domain_error for x <= 0
Interval sinh(const Interval& x);
Interval cosh(const Interval& x);
Interval tanh(const Interval& x);
// Inverses: any end outside the domain (acosh: x >= 1, atanh: |x| <= 1) throws
// std::domain_error; atanh(+-1) is +-infinity.
Interval asinh(const Interval& x);
Interval acosh(const Interval& x);
Interval atanh(const Interval& x);

// Joint angle from its half-angle tangent t = tan(phi/2) in a sub-problem shifted by
// `half_turns` * pi: phi = 2 atan(t) + half_turns * pi.
Interval angle_from_half_tangent(const Interval& t, int half_turns);

// MPFR keeps per-thread caches (constants, arctangent tables) that a thread's exit does not
// free: a thread that used these functions calls this before it ends.
void release_thread_caches();

}  // namespace linkbox::rigorous
