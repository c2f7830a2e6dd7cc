#pragma once
// Functions of variables lifted to polynomial equations in new unknowns, so that the rest of
// linkbox (propagation, Newton, LP, certification) sees a polynomial system (and links, for
// the functions no polynomial relates to their argument), and the record that maps its roots
// back to the case's own variables one to one.
//
//  - A variable t used only inside sin, cos and tan is an angle. Each argument must be
//    affine, a*t + b (several angles may be summed), and the coefficients of one angle must
//    be integer multiples of one unit w > 0: u = w*t is then the angle that is modelled, and
//    sin/cos of k*u + b expand into polynomials in cos(u), sin(u) (angle-sum and multiple-
//    angle formulas). What the case uses decides the unknowns:
//      circle    c = cos(u), s = sin(u) with c^2 + s^2 = 1 and, when u's domain is less than
//                a full turn and not within one quadrant, the half-plane c cos m + s sin m >=
//                cos h (m its centre, h its half-width), which is exactly the arc of the
//                domain (the box of (c, s) alone holds more of the circle);
//      cos only  c alone, when s never occurs and u's domain lies within one [k pi, (k+1) pi]
//                (cos is one to one there);
//      sin only  s alone, when c never occurs and u's domain lies within [k pi - pi/2,
//                k pi + pi/2];
//      tan only  tau = tan(a*t + b) alone, when that is the angle's only use.
//    A domain wider than a full turn (u's width provably > 2 pi) is rejected: the map back
//    from (c, s) would not be one to one. A full turn (e.g. [-pi, pi]) is the whole circle:
//    a root on the seam is one root, reported near the domain's upper end.
//    sin or cos of a multiple or a sum of angles (an expansion of degree 2 or more) that is
//    multiplied by an expression with variables, or raised, is an unknown y with the
//    equation y - (its expansion) = 0: expanded, C cos(3t) is C (4 c^3 - 3 c), whose C
//    occurs twice, so interval evaluation overestimates it; C y keeps it exact. Its domain
//    is sin or cos of the argument's range.
//    sin, cos and tan of anything else (an argument that is not affine, or has a variable
//    that also occurs outside sin, cos and tan) are links, below: t and cos(t) are not related
//    by any polynomial equation. tan's argument must stay within one branch (pi/2 + k pi
//    excluded) over the domain.
//  - tan(A) of an angle expression that is not "tan only": an unknown tau with tau cos(A) =
//    sin(A); A's range over the domain must avoid the poles (tau's domain is tan of it).
//  - base: a sum A over two or more variables raised to a power, where the reader keeps it as
//    written (input/expression.hpp: the peers' readers), e.g. (x - y)^3: an unknown b with
//    the equation b - A = 0 and A's range as its domain, so that A^k is b^k, and every
//    product of A with an expression with variables (exp(z) * A) is a product with b.
//    Expanded, A^3 is a sum of terms that cancel, which interval evaluation cannot see (near
//    x = y = 200 with widths of 1e-3 it spans hundreds); b^3 keeps it. Its roots are the
//    case's one to one (b is a function of the variables). A sum that is never raised, or
//    that holds a cleared divisor (below), is expanded.
//  - sqrt(A) (and A^(k + 1/2)) of any expression: an unknown r with r^2 = A, r >= 0 (the
//    domain of r is [0, sqrt(max A)]).
//  - 1/B (a division by an expression with variables, A/B = A * (1/B)): an unknown q with
//    q B = 1 when B's range over the domain excludes 0 (q's domain is 1/that range). The
//    roots correspond one to one: q B = 1 forces B != 0 and q = 1/B, so no root is lost and
//    none is added (not even where A = B = 0, which q B - A = 0 would admit), and a root
//    certified in the lifted system is one of the case's.
//  - 1/B where B's range may hold 0 (or is unbounded, or B divides by such a divisor): B is
//    cleared. An equation of degree m in q = 1/B is multiplied by B^m, an inequality by B^e
//    (e = m rounded up to even, so its sign is kept), which leaves polynomials (later
//    divisors first, as a divisor may hold earlier quotients); and the strict inequality
//    -B^2 < 0 is added. Where B != 0 the cleared constraints hold exactly where the case's
//    do, so no root is lost; where B = 0 the case's expressions are undefined and -B^2 < 0
//    fails, so no such point is counted (a root of the cleared equations where the enclosure
//    cannot decide the sign of B is unresolved, as on any inequality's boundary). Any other
//    function of an expression holding such a quotient is refused (its range is unbounded).
//  - atan2(Y, X) of any expressions: an unknown t with the links c = cos(t), s = sin(t), the
//    equation X s - Y c = 0 and the strict inequality X c + Y s > 0. Together they say that
//    (c, s) is the direction of (X, Y) != 0, so t = atan2(Y, X) up to a multiple of 2 pi; and
//    the system is square and regular in (t, c, s) there (the determinant is |(X, Y)| > 0).
//    t's domain is atan2 of the ranges of Y and X; where that spans 2 pi (the ranges cross
//    the cut, the negative X axis) -pi < t <= pi is added, which keeps one t per point. A
//    point with X = Y = 0 fails the strict inequality; a root on the cut itself (Y = 0,
//    X < 0) is on the boundary of t <= pi, so it is at best unresolved, never counted twice.
//  - exp, log, sinh, cosh, tanh, asinh, acosh, atanh, asin, acos, atan (and sin, cos, tan as above) of
//    any expression
//    A, which no polynomial relates to its argument: an unknown y and a link y = f(a)
//    (model/link.hpp), used only where no polynomial lifting applies, where a is A
//    itself when A is one variable, else a new unknown with the equation a - A = 0. The
//    domain of y is f(range of A), which must be bounded (log: A's range must stay above 0);
//    the domain of a is A's range within f's domain (log: a >= 0; asin, acos: [-1, 1]), which
//    only drops points where f is not defined. Roots correspond one to one (y and a are
//    functions of the declared variables).
// Every coefficient and domain is enclosed rigorously (MPFI for sin, cos, tan, atan2 and the
// functions of links).
#include "model/polynomial.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace linkbox::model {

// A function applied to an expression with variables, as the parser meets it. In a
// RawSystem, variable index n + k (n = declared variables) stands for application k.
struct Application {
  enum class Function {
    sin, cos, tan, sqrt, exp, log, sinh, cosh, tanh, asinh, acosh, atanh, asin, acos, atan, atan2, reciprocal, base
  };
  Function function;
  Polynomial argument;  // over the declared variables and the applications before this one
  std::string text;     // as written, e.g. "sin(2*t + pi/4)": names and messages
  bool raised = false;  // base: raised to a power somewhere (else it is expanded in place)
  Polynomial second;    // atan2(argument, second): X of atan2(Y, X); empty for the others
};
const char* to_string(Application::Function f);
// An enclosure of the application's value where its argument is in `x` (reciprocal: 1/x;
// atan2: where X is in `second`). Throws std::domain_error when no point of x is in the
// function's domain (sqrt: x < 0; tan: a pole; reciprocal: x holds 0; log: x <= 0; asin,
// acos: outside [-1, 1]; atan2: x and second both 0).
Interval enclose(const Application& a, const Interval& x, const Interval& second = Interval(1.0));
// The same where the declared variables and the earlier applications' values are `values`.
Interval enclose_over(const Application& a, const Box& values);
// The link function of `f` (exp, log, sinh, cosh, tanh, asin, acos, atan); false for the
// functions lifted to polynomial equations.
bool link_function(Application::Function f, Elementary& out);

// A system as typed, before lifting: equations and inequalities over the declared
// variables and the applications.
struct RawSystem {
  std::vector<Variable> variables;
  std::vector<Polynomial> equations;
  std::vector<std::string> equation_names;
  std::vector<Inequality> inequalities;
  std::vector<Application> applications;
  std::vector<std::string> interval_constants;  // as System::interval_constants
  std::vector<std::string> assumed_bounds;      // as System::assumed_bounds
};

// What cannot be lifted. `variable` (declared index), `application`, `equation` or
// `inequality` locates the cause for the caller's message (-1: not that one).
struct LiftError : std::invalid_argument {
  int variable = -1, application = -1, equation = -1, inequality = -1;
  LiftError(const std::string& message, int variable, int application, int equation = -1, int inequality = -1)
      : std::invalid_argument(message),
        variable(variable),
        application(application),
        equation(equation),
        inequality(inequality) {}
};

struct Lifting {
  enum class Chart { circle, cos_only, sin_only, tan_only };
  // A declared variable t used as an angle: u = unit * t is modelled.
  struct Angle {
    int variable = -1;
    Interval unit{1.0};  // > 0
    Interval domain;     // of u: unit * (domain of t)
    Chart chart = Chart::circle;
    int c = -1, s = -1;  // lifted indices of cos(u), sin(u) (-1: not modelled)
    int tan = -1;        // tan only: lifted index of tan(u * sign + offset)
    Interval offset{0.0};  // tan only: tan(sign * u + offset) is modelled
    int sign = 1;          // tan only
    long branch = 0;       // cos/sin/tan only: which monotone branch u's domain lies in
    double centre = 0;     // circle: u is reported in [centre - pi, centre + pi] (see to_declared)
    Interval cos_centre{1.0}, sin_centre{0.0};  // enclosures of cos and sin of `centre`
    bool full_turn = false;
  };
  // Where each lifted variable comes from.
  struct Source {
    enum class Kind { declared, cos, sin, tan_angle, application, argument, angle_cos, angle_sin } kind;
    // declared variable, angle, angle, application, application (a link's argument),
    // application (cos and sin of an atan2's value)
    int index;
  };

  std::vector<Variable> declared;         // the case's own variables: what is reported
  std::vector<Application> applications;  // as parsed
  std::vector<Angle> angles;
  std::vector<Source> sources;            // one per lifted variable
  std::vector<bool> cleared;              // per application: a cleared divisor's 1/B (no unknown)
  std::vector<std::string> notes;         // what was lifted, one line each

  // Rigorous enclosure of the declared variables over a box of lifted ones. Every point of
  // the box that satisfies the lifted system maps into it (angles by atan2, acos, asin,
  // atan on their branch).
  Box to_declared(const Box& lifted) const;
  // Rigorous enclosure of the lifted variables over a box of declared ones (the functions of
  // the arguments, and the arguments of links). Throws std::domain_error (see enclose) when
  // the box meets a pole of a tan, makes a sqrt's argument negative throughout, and so on.
  Box to_lifted(const Box& declared) const;
};

// Lifts `raw`. Without applications the result is `raw` as a System with no lifting record.
// Throws LiftError for what cannot be lifted (see the top of this file).
System lift(const RawSystem& raw);

// `p` with variable i replaced by images[i] (every variable of p needs an image).
Polynomial substitute(const Polynomial& p, const std::vector<Polynomial>& images);

// Whether two polynomials have the same terms with the same coefficient bounds.
bool same(const Polynomial& a, const Polynomial& b);

}  // namespace linkbox::model
