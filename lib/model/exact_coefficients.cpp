#include "model/exact_coefficients.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

namespace linkbox::model {

std::optional<Rational> exact_coefficient(const Polynomial& p, const Powers& powers, const Interval& c) {
  if (c.lower() == c.upper()) {
    if (!std::isfinite(c.lower())) return std::nullopt;
    return Rational(c.lower());
  }
  if (!p.exact()) return std::nullopt;
  auto it = p.exact()->values.find(powers);
  if (it == p.exact()->values.end()) return std::nullopt;
  return it->second;
}

Interval enclosure(const Rational& value) {
  const double d = value.convert_to<double>();
  if (!std::isfinite(d)) {
    const double big = std::numeric_limits<double>::max();
    return value > 0 ? Interval(big, std::numeric_limits<double>::infinity())
                     : Interval(-std::numeric_limits<double>::infinity(), -big);
  }
  const Rational at(d);
  if (at == value) return Interval(d);
  return at < value ? Interval(d, std::nextafter(d, std::numeric_limits<double>::infinity()))
                    : Interval(std::nextafter(d, -std::numeric_limits<double>::infinity()), d);
}

std::optional<Rational> exact_decimal(std::string_view literal) {
  constexpr long kMaxPower = 4000;  // 10^-4000: far below any finite double
  std::string digits;
  long power = 0;
  size_t i = 0;
  for (; i < literal.size() && std::isdigit(static_cast<unsigned char>(literal[i])); ++i) digits += literal[i];
  if (i < literal.size() && literal[i] == '.')
    for (++i; i < literal.size() && std::isdigit(static_cast<unsigned char>(literal[i])); ++i, --power)
      digits += literal[i];
  if (digits.empty()) return std::nullopt;
  if (i < literal.size() && (literal[i] == 'e' || literal[i] == 'E')) {
    const std::string exponent(literal.substr(i + 1));
    if (exponent.empty() || exponent.size() > 8) return std::nullopt;
    size_t used = 0;
    try {
      power += std::stol(exponent, &used);
    } catch (const std::exception&) {
      return std::nullopt;
    }
    if (used != exponent.size()) return std::nullopt;
    i = literal.size();
  }
  if (i != literal.size() || std::labs(power) > kMaxPower) return std::nullopt;
  using Integer = boost::multiprecision::mpz_int;
  const Integer ten_power = boost::multiprecision::pow(Integer(10), static_cast<unsigned>(std::labs(power)));
  digits.erase(0, std::min(digits.find_first_not_of('0'), digits.size() - 1));  // "012" would read as octal
  const Rational mantissa{Integer(digits)};
  return power >= 0 ? mantissa * Rational(ten_power) : mantissa / Rational(ten_power);
}

}  // namespace linkbox::model
