#pragma once
// Sparse polynomials with interval coefficients, and the systems linkbox solves.
#include "interval/box.hpp"
#include "model/link.hpp"

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace linkbox::model {

// Exponents by variable index, sorted by index, no zero exponents.
using Powers = std::vector<std::pair<int, int>>;

struct ExactCoefficients;  // model/exact_coefficients.hpp
struct ExactValue;

class Polynomial {
 public:
  Polynomial() = default;
  static Polynomial constant(const Interval& c);
  static Polynomial variable(int index);
  static Polynomial monomial(const Powers& powers, const Interval& coefficient);
  // The decimal `literal` (digits, an optional fraction and exponent) as a constant: its
  // enclosure, and its exact value where that is not a double. Throws std::invalid_argument
  // when malformed.
  static Polynomial decimal(std::string_view literal);

  const std::map<Powers, Interval>& terms() const { return terms_; }
  bool is_zero() const { return terms_.empty(); }
  bool is_constant() const;
  Interval constant_term() const;

  Polynomial& operator+=(const Polynomial& o);
  Polynomial& operator-=(const Polynomial& o);
  Polynomial& operator*=(const Interval& c);
  // Division by a constant `d` whose enclosure excludes 0, coefficient by coefficient.
  Polynomial& operator/=(const Polynomial& d);
  friend Polynomial operator+(Polynomial a, const Polynomial& b) { return a += b; }
  friend Polynomial operator-(Polynomial a, const Polynomial& b) { return a -= b; }
  friend Polynomial operator*(const Polynomial& a, const Polynomial& b);
  friend Polynomial operator*(Polynomial a, const Interval& c) { return a *= c; }
  Polynomial operator-() const;
  Polynomial pow(int exponent) const;
  // A constant's power, its enclosure by one interval power (x^2 >= 0).
  Polynomial constant_power(int exponent) const;

  // The exact value of each coefficient that is not a point: where every one is known, the
  // polynomial's exact coefficients are known, as the exact tests of verify/ need. Decimals
  // as written, and sums, products and quotients of known values, are known; an interval
  // constant, pi or a function's value is not. Null when no coefficient's value is held.
  const ExactCoefficients* exact() const { return exact_.get(); }

  // Natural interval extension (even powers evaluated as such, so x^2 >= 0).
  Interval eval(const Box& box) const;
  // Partial derivative with respect to variable `index`.
  Polynomial derivative(int index) const;
  // Sorted indices of the variables that occur.
  std::vector<int> variables() const;
  int degree_in(int index) const;
  int total_degree() const;
  bool is_multi_affine() const;  // every exponent is 1
  std::string to_string(const std::vector<std::string>& names) const;

 private:
  // Adds c (exact value `q` where c is not a point and the value is known) to the term p.
  void add_term(const Powers& p, const Interval& c, const ExactValue* q = nullptr);
  void hold(std::map<Powers, Interval>::iterator term, const ExactValue& value);
  ExactCoefficients& exact_for_write();
  std::map<Powers, Interval> terms_;
  std::shared_ptr<ExactCoefficients> exact_;  // shared on copy, copied before a write
};

// Rigorous residual at the box's midpoint m (each coordinate the double nearest the centre
// of its side, a point of the box): an upper bound on max_i |f_i(m)| from the
// outward-rounded interval value of each f_i at m. 0 when there are no equations.
double residual_bound(const std::vector<Polynomial>& f, const Box& box);

struct Variable {
  std::string name;
  Interval domain;
};

// g(x) <= 0, or g(x) < 0 when strict. Interval coefficients stand for the true constants
// they enclose: a point is proved feasible only when g's enclosure there is <= 0 (< 0) for
// every choice of coefficients, and proved infeasible only when it is > 0 (>= 0) for every
// choice, so a rounded constant never decides a root's side.
struct Inequality {
  Polynomial g;
  bool strict = false;
  std::string name;  // for messages: as the user wrote it, e.g. "x + y <= 1"
  // An angle's domain as an arc (model/lifting.hpp): g <= 0 says that the point (c, s) =
  // (x[c], x[s]) of the unit circle is within `half` of the direction (cos_centre,
  // sin_centre). Near the far end of a wide arc g is flat in the angle (a root 1e-8 outside
  // the arc moves g by 5e-17), so side_of decides it by the angle instead.
  struct Arc {
    int c = -1, s = -1;
    Interval cos_centre, sin_centre, half;  // half < pi
    Interval domain;  // the angle's domain [lo, hi] itself, its ends exact doubles
  };
  std::optional<Arc> arc = std::nullopt;
};

// Where a box lies with respect to an inequality: every point satisfies it (inside), none
// does (outside), or the enclosure cannot tell (boundary: the box may straddle g = 0). For an
// arc, of the box's points on the unit circle (what the system's circle equation leaves).
enum class Side { inside, outside, boundary };
Side side_of(const Inequality& c, const Box& box);
const char* to_string(Side s);

struct Lifting;  // model/lifting.hpp

// A system of equations p_i = 0 and inequalities over named variables with domains.
struct System {
  std::vector<Variable> variables;
  std::vector<Polynomial> equations;
  std::vector<std::string> equation_names;  // same length as equations (may be empty strings)
  // Constraints that select among the roots: pruning may use them (a box where one provably
  // fails holds no root of interest); roots are reported only where all of them hold.
  std::vector<Inequality> inequalities;
  // Equations y = f(a) that are not polynomials (model/link.hpp); each counts as an equation.
  // Whatever proves a box empty or a root certified must see them: a contractor may ignore
  // them only where fewer constraints are still sound (a relaxation).
  std::vector<Link> links;
  // When the case's own variables were lifted (functions of variables, model/lifting.hpp):
  // how they follow from `variables` and back. Null: `variables` are the case's own.
  std::shared_ptr<const Lifting> lifting;
  // The genuine interval constants the coefficients use (as written, e.g. "[0.9, 1.1]"): the
  // system is then a family, and its roots are claimed for every value of them.
  std::vector<std::string> interval_constants;
  // Variables whose domain the case file left unbounded, as bounded by default ("x in [-1e8,
  // 1e8]", input/unbounded_domain.hpp): every claim is within them.
  std::vector<std::string> assumed_bounds;

  Box domain() const;
  bool is_multi_affine() const;
  int index_of(const std::string& name) const;  // -1 when absent
  std::vector<std::string> names() const;
};

}  // namespace linkbox::model
