#pragma once
// Text -> polynomial with rigorous interval coefficients, for equations and numbers typed in
// case files. Every decimal literal is enclosed as the decimal the user wrote (0.0175 is not a
// double) and every constant sub-expression is folded with rigorous::, so a constant's
// interval provably contains the real value the text denotes.
//
// Grammar (whitespace anywhere between tokens):
//   expr    := term (('+' | '-') term)*
//   term    := unary (('*' | '/') unary)*
//   unary   := ('-' | '+') unary | power
//   power   := primary ('^' unary)?          right-associative: 2^3^2 = 2^9
//   primary := number | 'pi' | variable | function '(' expr ')' | '(' expr ')'
//            | '[' expr ',' expr ']'       an interval constant, where `intervals` is given
//   number  := digits ['.' digits] | '.' digits, then optionally [eE][+-]digits
//   function: sin cos tan asin acos atan sqrt exp log sinh cosh tanh abs sign, and min and max
//   of two arguments ('(' expr ',' expr ')'), of constant arguments only.
// Exponents are exact non-negative integers (at most kMaxExponent); divisors are constant
// expressions whose interval excludes 0.
//
// parse_with_functions also admits every function of expressions with variables, exponents
// k + 1/2 (x^(1/2) is sqrt(x)), negative ones (A^-e is 1/A^e) and divisors with variables
// (A/B is A * (1/B)); abs(A) is sqrt(A^2), min and max (A + B -+ |A - B|) / 2, sign(A) A/|A|.
// They are kept as model::Application for model::lift, which turns them into new unknowns
// with polynomial equations or links (model/lifting.hpp).
//
// An interval constant [a, b] (constant ends, a <= b) is the interval from the lower end of
// a's enclosure to the upper end of b's: each use is one interval coefficient, standing for
// every value in it (docs/verification.md says what a certified root then means).
#include "model/lifting.hpp"
#include "model/polynomial.hpp"

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace linkbox::input {

inline constexpr int kMaxExponent = 1000;

// The genuine interval constants a text uses: each distinct literal "[a, b]" as written,
// unless it is a point (both ends the same text, or the same double).
using IntervalConstants = std::vector<std::string>;

// what() is the bare message; `column` is the 0-based byte offset in the parsed text.
struct ParseError : std::runtime_error {
  int column;
  ParseError(const std::string& message, int column) : std::runtime_error(message), column(column) {}
};

// Parses `text` as a polynomial in `variables` (variable i of the result = variables[i]).
// A declared variable named like a constant (`pi`) shadows it.
model::Polynomial parse_polynomial(std::string_view text, const std::vector<std::string>& variables);

// Like parse_polynomial, but functions of expressions with variables (and exponents k + 1/2,
// and divisors with variables) become applications: each distinct one is appended to `applications`
// once (an equal one already there is reused) and stands for variable
// variables.size() + its index. With `intervals`, interval constants are allowed and listed
// there (null: they are an error).
//
// With Powers::as_written, a parenthesised sum A over two or more variables that is raised to
// a power somewhere is an application too (model::Application::Function::base), which
// model::lift makes one unknown, shared by the power and by every product of A with an
// expression with variables ((x - y)^3, exp(z) * (x - y)); a sum that is only ever multiplied
// is expanded. The roots are the same; the unknown keeps interval evaluation from losing the
// cancellation between the expanded terms, as the peers' expression graphs do. The peers'
// readers read so; the TOML reader expands (Powers::expanded), so that a TOML case's unknowns
// are those it declares and its functions', in which its curve maps are stated.
enum class Powers { expanded, as_written };
model::Polynomial parse_with_functions(std::string_view text, const std::vector<std::string>& variables,
                                       std::vector<model::Application>& applications,
                                       IntervalConstants* intervals = nullptr, Powers powers = Powers::expanded);

// An equation "lhs = rhs" (lhs - rhs = 0) or an expression (= 0), with functions as above.
model::Polynomial parse_equation(std::string_view text, const std::vector<std::string>& variables,
                                 std::vector<model::Application>& applications,
                                 IntervalConstants* intervals = nullptr);

// "lhs <= rhs", ">=", "<" or ">" as g <= 0 (strict for < and >), g = lhs - rhs (or rhs - lhs),
// with functions as above. `name` of the result is the text.
model::Inequality parse_inequality(std::string_view text, const std::vector<std::string>& variables,
                                   std::vector<model::Application>& applications,
                                   IntervalConstants* intervals = nullptr, Powers powers = Powers::expanded);

// Parses a constant expression such as "pi/2", "acos(-1/3)" or "-0.7448995469549714"; with
// `intervals`, one that uses interval constants too (its value encloses every value).
Interval parse_constant(std::string_view text, IntervalConstants* intervals = nullptr);

// Whether `name` may be used as a variable name in an expression (identifier syntax, not a
// constant or function name).
bool is_valid_variable_name(std::string_view name);

}  // namespace linkbox::input
