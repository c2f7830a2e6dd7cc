#pragma once
// What the expression parser (expression.cpp) knows without any state of its own: its
// functions and how each folds a constant, the names and characters of its grammar, and the
// polynomial and number helpers it builds with.
#include "model/lifting.hpp"
#include "model/polynomial.hpp"

#include <string>
#include <string_view>

namespace linkbox::input::expression_vocabulary {

using Lifted = model::Application::Function;

// A function of one argument: how it folds a constant, and the application it becomes.
struct Function {
  std::string_view name;
  Interval (*apply)(const Interval&);
  bool liftable;  // of variables too, through model::lift
  Lifted lifted;
};
const Function* find_function(std::string_view name);
// The number of arguments of a function the parser handles itself (Parser::special): abs and
// sign (1) and min and max (2), written through sqrt and division, and atan2 (2), an
// application of two arguments; 0 for any other name.
int special_arity(std::string_view name);

bool is_identifier_start(char c);
bool is_identifier_char(char c);
bool is_digit(char c);
bool is_nan_or_inf_name(std::string_view name);
std::string describe(char c);  // 'x', or "byte 0x07" for an unprintable one
std::string_view trim(std::string_view s);

// A sum whose terms may cancel: two or more terms, over two or more variables.
bool is_sum(const model::Polynomial& p);
model::Polynomial monomial(const model::Powers& powers);
// c, B's first coefficient, when it is positive and B / c has exact coefficients (`normal`);
// else 1.
double exact_scale(const model::Polynomial& b, model::Polynomial& normal);
std::string shortest(double x);  // the shortest decimal that reads back as x

}  // namespace linkbox::input::expression_vocabulary
