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

// When every coefficient of `h` has a known exact value (model/exact_coefficients.hpp), `point` (rationals as simplest_rational writes
// them, one per unknown) is an exact zero of every equation, and the Jacobian there has rank
// exactly n - 2: the kind of that singular point. Otherwise none.
std::optional<SingularKind> exact_singular_kind(const std::vector<model::Polynomial>& h,
                                                const std::vector<std::string>& point);

// The rational `text` (as above) lies in `x` (exact comparison); false when malformed.
bool rational_in(const std::string& text, const Interval& x);

// Exact roots. A certified root's box may hold a rational point (the simplest rational in
// each side) where every equation, at its coefficients' exact values, is exactly zero: that point is
// the root, the only one in the box. Where it lies is then decided exactly, also on a face of
// the domain or on an inequality's boundary, where enclosures cannot tell.

// That point of `box`, one rational per unknown; none when some equation is not exactly 0.
std::optional<std::vector<std::string>> exact_zero_in(const std::vector<model::Polynomial>& f, const Box& box);
// Whether the exact value of every coefficient of `f` is known, as every exact test here
// needs: a double, a decimal as written (0.1), and what exact arithmetic makes of them are;
// pi, a function's value (sin(1), sqrt(2)) and an interval constant are not.
bool known_coefficients(const std::vector<model::Polynomial>& f);
// Whether every equation of `f` is exactly 0 at `point`.
bool exact_zero(const std::vector<model::Polynomial>& f, const std::vector<std::string>& point);
// Whether `point` lies in `box` (exact comparisons).
bool rationals_in(const std::vector<std::string>& point, const Box& box);
// Both: `point` is a root of `f` in `box` (with a certificate's image, the root there).
bool exact_root_in(const std::vector<model::Polynomial>& f, const std::vector<std::string>& point, const Box& box);
// The side of `c` at `point`: a polynomial inequality by the exact sign of g (known
// coefficients; otherwise boundary), an angle's domain arc by the point's angle theta on the
// unit circle. theta + 2 k pi is never a double unless it is 0 (at (1, 0), theta = 0 exactly;
// at any other rational point of the circle e^{i theta} is algebraic with theta != 0, so by
// Lindemann-Weierstrass theta + 2 k pi is transcendental), so an enclosure at high enough
// precision decides it against the domain's ends, and 0 is compared exactly.
model::Side exact_side(const model::Inequality& c, const std::vector<std::string>& point);
// The side of `c` on a certified root's box, or, where that is undecided, at its exact root
// (none: empty).
model::Side side_of_root(const model::Inequality& c, const Box& box, const std::vector<std::string>& exact);

}  // namespace linkbox::verify
