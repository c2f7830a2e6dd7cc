#pragma once
// The exact rational values behind a polynomial's interval coefficients (model/polynomial.hpp):
// a decimal such as 0.1 is held as an interval around it, and its value as written beside it,
// so that exact tests (verify/exact_point.hpp) see the system the user wrote.
#include "model/polynomial.hpp"

#include <boost/multiprecision/gmp.hpp>

#include <map>
#include <optional>
#include <string_view>

namespace linkbox::model {

using Rational = boost::multiprecision::mpq_rational;

struct ExactValue {
  Rational q;
};

// The exact value of each coefficient that is not a point and whose value is known.
struct ExactCoefficients {
  std::map<Powers, Rational> values;
};

// The exact value of a coefficient `c` of `p` at `powers`: c itself when a point, the value
// `p` holds otherwise; none when it is not known or not finite.
std::optional<Rational> exact_coefficient(const Polynomial& p, const Powers& powers, const Interval& c);

// The tightest interval of doubles holding `value` (a point when it is a double).
Interval enclosure(const Rational& value);

// The decimal `literal` (digits, an optional fraction and exponent) as an exact rational;
// none when malformed or when its power of ten is far beyond a double's range.
std::optional<Rational> exact_decimal(std::string_view literal);

}  // namespace linkbox::model
