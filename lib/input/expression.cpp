// The grammar of input/expression.hpp: sums, products, powers, numbers, names and interval
// constants (the parser's functions are in expression_functions.cpp).
#include "input/expression_parser.hpp"

#include "interval/rigorous.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace linkbox::input {

namespace detail {

using namespace expression_vocabulary;

Value Parser::expression() {
  Value v = term();
  for (char op = peek(); op == '+' || op == '-'; op = peek()) {
    v.group.clear();
    const size_t at = pos_++;
    Value rhs = term();
    if (op == '+')
      v.poly += rhs.poly;
    else
      v.poly -= rhs.poly;
    v.has_variable |= rhs.has_variable;
    check_finite(v, at);
  }
  return v;
}

Value Parser::term() {
  Value v = unary();
  for (char op = peek(); op == '*' || op == '/'; op = peek()) {
    const size_t at = pos_++;
    const size_t rhs_at = next_token();
    Value rhs = unary();
    if (op == '*' && v.has_variable && rhs.has_variable)
      v = multiply(as_written(v, false), as_written(rhs, false), at);
    else if (op == '*')
      v = multiply(v, rhs, at);
    else if (rhs.has_variable && applications_ && !rhs.poly.is_constant())
      v = multiply(v, reciprocal(rhs, rhs_at), at);
    else
      v = divide(v, rhs, rhs_at);
    check_finite(v, at);
  }
  return v;
}

Value Parser::unary() {
  const char c = peek();
  if (c != '-' && c != '+') return power();
  const size_t at = pos_++;
  Nesting guard(*this, at);
  Value v = unary();
  v.group.clear();
  if (c == '-') v.poly = -v.poly;
  return v;
}

Value Parser::power() {
  const size_t base_at = next_token();
  Value base = primary();
  if (peek() != '^') return base;
  const size_t at = pos_++;
  const size_t exponent_at = next_token();
  Nesting guard(*this, at);
  Value exponent = unary();  // right-associative
  if (is_negative_constant(exponent)) {
    // A^-e = 1 / A^e: the reciprocal of the power (an unknown q with q A^e = 1, or cleared).
    exponent.poly = -exponent.poly;
    const double e = exponent.constant().lower();
    const std::string power_text =
        std::string(trim(text_.substr(base_at, at - base_at))) + (e == 1 ? "" : "^" + shortest(e));
    const Value p = raise(base, exponent, base_at, at, exponent_at);
    if (p.has_variable && !applications_) fail("exponent must be a non-negative integer constant", exponent_at);
    if (p.has_variable && !p.poly.is_constant()) return reciprocal(p, power_text);
    return divide(Value{Polynomial::constant(Interval(1.0)), false}, p, base_at);
  }
  return raise(base, exponent, base_at, at, exponent_at);
}

bool Parser::is_negative_constant(const Value& e) {
  const Interval x = e.constant();
  return !e.has_variable && x.lower() == x.upper() && x.upper() < 0;
}

Value Parser::raise(Value base, const Value& exponent, size_t base_at, size_t at, size_t exponent_at) {
  if (applications_ && is_half_integer(exponent)) return half_power(base, exponent, base_at, at, exponent_at);
  const int n = integer_exponent(exponent, exponent_at);
  Value r{Polynomial::constant(Interval(1.0)), base.has_variable};
  if (n == 0) return r;  // x^0 = 1, also for 0^0 (Boost's pow would return empty)
  if (n >= 2) base = as_written(base, true);
  if (!base.has_variable) {
    r.poly = base.poly.constant_power(n);
  } else {
    for (int k = n; k > 0; k >>= 1) {  // square-and-multiply, guarded against blow-up
      if (k & 1) r = multiply(r, base, at);
      if (k > 1) base = multiply(base, base, at);
    }
  }
  check_finite(r, at);
  return r;
}

Value Parser::primary() {
  const char c = peek();
  const size_t at = pos_;
  if (pos_ == text_.size()) fail("expression ends where a number, variable or '(' was expected", at);
  if (is_digit(c) || (c == '.' && pos_ + 1 < text_.size() && is_digit(text_[pos_ + 1]))) return number();
  if (is_identifier_start(c)) return identifier();
  if (c == '(') {
    ++pos_;
    Nesting guard(*this, at);
    Value v = expression();
    expect_closing(at);
    const bool kept = powers_ == Powers::as_written && applications_ && is_sum(v.poly);
    v.group = kept ? std::string(text_.substr(at, pos_ - at)) : std::string();
    return v;
  }
  if (c == '[') return interval_constant();
  if (c == ')') fail("')' where a number, variable or '(' was expected", at);
  unexpected("a number, variable or '('");
}

// "[a, b]": the interval from the lower end of a's enclosure to the upper end of b's. Its
// text is listed in intervals_ unless it is a point (the same text twice, or one double).
Value Parser::interval_constant() {
  const size_t open_at = pos_++;
  Nesting guard(*this, open_at);
  if (!intervals_)
    fail("an interval constant ('[a, b]') is allowed only in equations and inequalities", open_at);
  const size_t lower_at = next_token();
  const Value lower = expression();
  const size_t comma_at = pos_;
  if (peek() != ',') unexpected("',' between the ends of the interval opened at column " + std::to_string(open_at));
  ++pos_;
  const size_t upper_at = next_token();
  const Value upper = expression();
  const size_t close_at = pos_;
  if (peek() != ']') {
    if (pos_ == text_.size()) fail("missing ']' for the '[' at column " + std::to_string(open_at), pos_);
    unexpected("']' (closing the '[' at column " + std::to_string(open_at) + ")");
  }
  ++pos_;
  if (lower.has_variable || upper.has_variable)
    fail("the ends of an interval constant must be constant expressions", open_at);
  const Interval a = lower.constant(), b = upper.constant();
  if (a.lower() > b.upper()) fail("empty interval constant: its lower end exceeds its upper end", open_at);
  const bool point = trim(text_.substr(lower_at, comma_at - lower_at)) ==
                         trim(text_.substr(upper_at, close_at - upper_at)) ||
                     (a.lower() == a.upper() && b.lower() == b.upper() && a.lower() == b.lower());
  const std::string text(text_.substr(open_at, pos_ - open_at));
  if (!point && std::find(intervals_->begin(), intervals_->end(), text) == intervals_->end())
    intervals_->push_back(text);
  return Value{Polynomial::constant(Interval(a.lower(), b.upper())), false};
}

Value Parser::number() {
  const size_t start = pos_;
  auto digits = [&] {
    size_t n = 0;
    for (; pos_ < text_.size() && is_digit(text_[pos_]); ++pos_) ++n;
    return n;
  };
  size_t mantissa_digits = digits();
  if (pos_ < text_.size() && text_[pos_] == '.') {
    ++pos_;
    mantissa_digits += digits();
  }
  if (mantissa_digits == 0) fail("malformed number", start);
  if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
    ++pos_;
    if (pos_ < text_.size() && (text_[pos_] == '+' || text_[pos_] == '-')) ++pos_;
    if (digits() == 0) fail("malformed number: exponent has no digits", start);
  }
  const std::string_view literal = text_.substr(start, pos_ - start);
  if (pos_ < text_.size() && is_identifier_char(text_[pos_]))
    fail("missing operator between the number " + std::string(literal) + " and " + describe(text_[pos_]) +
             " (write 2*x, not 2x)",
         pos_);
  Polynomial x;
  try {
    x = Polynomial::decimal(literal);
  } catch (const std::invalid_argument&) {
    fail("malformed number '" + std::string(literal) + "'", start);
  }
  if (!is_finite(x.constant_term()))
    fail("number " + std::string(literal) + " is outside the range of a double", start);
  return Value{x, false};
}

Value Parser::identifier() {
  const size_t start = pos_;
  while (pos_ < text_.size() && is_identifier_char(text_[pos_])) ++pos_;
  const std::string name(text_.substr(start, pos_ - start));
  for (size_t i = 0; i < variables_.size(); ++i)
    if (variables_[i] == name) return Value{Polynomial::variable(static_cast<int>(i)), true};
  if (name == "pi") return Value{Polynomial::constant(rigorous::pi()), false};
  const bool called = peek() == '(';
  if (const Function* f = find_function(name)) {
    if (!called) fail("function '" + name + "' needs a parenthesised argument", start);
    return call(*f, start);
  }
  if (special_arity(name) > 0) {
    if (!called) fail("function '" + name + "' needs a parenthesised argument", start);
    return special(name, start);
  }
  if (is_nan_or_inf_name(name)) fail("'" + name + "' is not allowed: numbers must be finite", start);
  if (called) fail("unknown function '" + name + "'", start);
  if (variables_.empty()) fail("unknown name '" + name + "' (a constant expression has no variables)", start);
  fail("unknown variable '" + name + "'", start);
}

bool Parser::is_half_integer(const Value& e) {
  const Interval x = e.constant();
  if (e.has_variable || x.lower() != x.upper() || x.lower() < 0) return false;
  const double twice = 2 * x.lower();  // exact: a double times 2
  return std::floor(twice) == twice && std::floor(x.lower()) != x.lower();
}

// base^(n + 1/2) = base^n * sqrt(base): a constant, or an application of sqrt.
Value Parser::half_power(const Value& base, const Value& exponent, size_t base_at, size_t at, size_t exponent_at) {
  const double e = exponent.constant().lower();
  if (e > kMaxExponent) fail("exponent is larger than " + std::to_string(kMaxExponent), exponent_at);
  const int n = static_cast<int>(std::floor(e));
  Value root;
  if (!base.has_variable) {
    try {
      root = Value{Polynomial::constant(rigorous::sqrt(base.constant())), false};
    } catch (const std::domain_error&) {
      fail("half-integer power of a negative number", at);
    }
  } else {
    root = application(Lifted::sqrt, base.poly,
                       "sqrt(" + std::string(trim(text_.substr(base_at, at - base_at))) + ")");
  }
  Value r = root;
  Value b = base;
  for (int k = n; k > 0; k >>= 1) {
    if (k & 1) r = multiply(r, b, at);
    if (k > 1) b = multiply(b, b, at);
  }
  check_finite(r, at);
  return r;
}

Value Parser::multiply(const Value& a, const Value& b, size_t at) {
  if (a.poly.terms().size() * b.poly.terms().size() > kMaxTermProducts)
    fail("expression expands to too many terms", at);
  return Value{a.poly * b.poly, a.has_variable || b.has_variable};
}

// Divides coefficient by coefficient: tighter than multiplying by an enclosure of 1/d.
Value Parser::divide(const Value& a, const Value& b, size_t divisor_at) {
  if (b.has_variable) fail("division by an expression with variables (only constant divisors)", divisor_at);
  const Interval d = b.constant();
  if (boost::numeric::zero_in(d)) fail("division by an interval containing zero", divisor_at);
  Polynomial r = a.poly;
  r /= b.poly;
  return Value{r, a.has_variable};
}

int Parser::integer_exponent(const Value& e, size_t at) {
  const Interval x = e.constant();
  if (e.has_variable || x.lower() != x.upper() || x.lower() < 0 || std::floor(x.lower()) != x.lower())
    fail(applications_ ? "exponent must be an integer or half-integer constant (x^(1/2) is sqrt(x))"
                       : "exponent must be a non-negative integer constant",
         at);
  if (x.lower() > kMaxExponent) fail("exponent is larger than " + std::to_string(kMaxExponent), at);
  return static_cast<int>(x.lower());
}

void Parser::check_finite(const Value& v, size_t at) {
  for (auto& [powers, c] : v.poly.terms())
    if (!is_finite(c)) fail("result is not finite (overflow)", at);
}

void Parser::expect_closing(size_t open_at) {
  if (peek() == ')') {
    ++pos_;
    return;
  }
  if (pos_ == text_.size()) fail("missing ')' for the '(' at column " + std::to_string(open_at), pos_);
  unexpected("')' (closing the '(' at column " + std::to_string(open_at) + ")");
}

// The parser stopped at a character that cannot continue the expression.
void Parser::unexpected(const std::string& expected) {
  const char c = text_[pos_];
  if (c == ')') fail("unmatched ')'", pos_);
  if (is_identifier_char(c) || c == '(' || c == '.') fail("missing operator before " + describe(c), pos_);
  fail("unexpected character " + describe(c) + ", expected " + expected, pos_);
}

}  // namespace detail

using detail::Parser;
using namespace expression_vocabulary;

model::Polynomial parse_polynomial(std::string_view text, const std::vector<std::string>& variables) {
  return Parser(text, variables).parse().poly;
}

model::Polynomial parse_with_functions(std::string_view text, const std::vector<std::string>& variables,
                                       std::vector<model::Application>& applications, IntervalConstants* intervals,
                                       Powers powers) {
  return Parser(text, variables, &applications, intervals, powers).parse().poly;
}

Interval parse_constant(std::string_view text, IntervalConstants* intervals) {
  static const std::vector<std::string> none;
  return Parser(text, none, nullptr, intervals).parse().constant();
}

bool is_valid_variable_name(std::string_view name) {
  if (name.empty() || !is_identifier_start(name[0])) return false;
  for (char c : name)
    if (!is_identifier_char(c)) return false;
  return name != "pi" && !find_function(name) && special_arity(name) == 0 && !is_nan_or_inf_name(name);
}

}  // namespace linkbox::input
