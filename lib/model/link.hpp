#pragma once
// A link: x[y] = f(x[a]) for a univariate elementary function f, the one equation of a lifted
// system that is not a polynomial (model/lifting.hpp makes one for a function of variables
// that no polynomial equation relates to them, e.g. exp(x) where x also occurs outside exp).
//
// Everything here is an outward-rounded enclosure through MPFI (interval/rigorous.hpp): the
// images, the derivatives, the inverses. f is defined on its domain (log: x > 0; asin, acos:
// [-1, 1]; acosh: x >= 1; atanh: -1 < x < 1; tan: every real off its poles; the others: every
// real) and a link holds only there, so a box's part outside the domain holds no point of the
// link: narrowing a box to the domain (closed: atanh's to [-1, 1], where its image is infinite)
// loses no root. tan is enclosed on a box within one branch; on a box that meets a pole
// (which the lifter keeps out of an argument's domain) nothing is learnt from it.
#include "interval/box.hpp"

#include <string>
#include <vector>

namespace linkbox::model {

enum class Elementary { exp, log, sinh, cosh, tanh, asinh, acosh, atanh, asin, acos, atan, sin, cos, tan };
const char* to_string(Elementary f);

// The k with x strictly inside (k pi - pi/2, k pi + pi/2): a branch of tan without a pole.
bool within_tan_branch(const Interval& x, long& k);

// One link's image, inverse or derivative through MPFI costs about this many interval
// products (prune::Counters::operations' unit).
constexpr double kLinkOperations = 300;

struct Link {
  Elementary f;
  int y = -1, a = -1;  // variable indices: x[y] = f(x[a])
  std::string name;    // for messages, e.g. "exp(x - y)"
};

// An enclosure of {f(v) : v in x, v in f's domain}. Throws std::domain_error when no point of
// x is in the domain.
Interval image(Elementary f, const Interval& x);
// Whether x lies in f's domain, so that image(f, x) encloses f over all of x (f continuous on x).
bool within_domain(Elementary f, const Interval& x);
// An enclosure of f' over x when f is continuously differentiable on all of x (x within the
// interior of asin's and acos's domain); the whole line otherwise.
Interval derivative(Elementary f, const Interval& x);

// The link's row as interval Newton sees it, r = y - f(a) for y, a the box's sides x[l.y],
// x[l.a]: its enclosure, and its partial derivative in x[a] (in x[y] it is 1). Both are the
// whole line unless f is continuous (value) or continuously differentiable (derivative) on
// all of a, so a Newton test proves nothing across the edge of f's domain.
Interval row_value(const Link& l, const Interval& y, const Interval& a);
Interval row_derivative(const Link& l, const Interval& a);
// The same in plain double, for float Newton's guesses only (NaN outside the domain).
double row_value_float(const Link& l, const double* x);
double row_derivative_float(const Link& l, const double* x);

// Narrows box[a] to f's domain and to f^-1(box[y]) (where f is monotone, or cosh's two
// branches), and box[y] to f(box[a]). False when the link provably holds nowhere in the box
// (its contents are then unspecified). Never removes a point (y, a) with y = f(a).
bool narrow(const Link& l, Box& box);
// Whether the link may hold somewhere in the box: false is a proof that it does not.
bool may_hold(const Link& l, const Box& box);
// An upper bound on |x[y] - f(x[a])| at the box's midpoint (0 when the midpoint's a is outside
// f's domain): for reports, as model::residual_bound.
double residual_bound(const std::vector<Link>& links, const Box& box);

}  // namespace linkbox::model
