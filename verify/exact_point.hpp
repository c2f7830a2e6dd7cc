#pragma once
// Exact rational arithmetic at one point of a polynomial system: whether a point is a zero,
// the rank of the Jacobian there, and the second-order form that tells what a rank drop of
// one is. Used where interval arithmetic can only say "contains 0" (a singular point).
#include "model/polynomial.hpp"

#include <optional>
#include <string>
#include <vector>

namespace linkbox::verify {

// What the zero set of n - 1 equations in n unknowns is near a point where the Jacobian has
// rank n - 2, from the reduced equation's Hessian Q (e^T H'' on the 2-dimensional kernel,
// e spanning the left kernel): det Q < 0, two smooth branches crossing transversally (a
// simple bifurcation point); det Q > 0, an isolated point of the zero set; det Q = 0, not
// decided by second order (a cusp, a tangency, a higher degeneracy).
enum class SingularKind { crossing, isolated, degenerate };
const char* to_string(SingularKind k);

// The simplest rational (smallest denominator) in [lo, hi], as "a" or "a/b"; none when lo
// > hi, an end is not finite, or no such rational is found within a bounded search.
std::optional<std::string> simplest_rational(double lo, double hi);

// When every coefficient of `h` is a point, `point` (rationals as simplest_rational writes
// them, one per unknown) is an exact zero of every equation, and the Jacobian there has rank
// exactly n - 2: the kind of that singular point. Otherwise none.
std::optional<SingularKind> exact_singular_kind(const std::vector<model::Polynomial>& h,
                                                const std::vector<std::string>& point);

// The rational `text` (as above) lies in `x` (exact comparison); false when malformed.
bool rational_in(const std::string& text, const Interval& x);

}  // namespace linkbox::verify
