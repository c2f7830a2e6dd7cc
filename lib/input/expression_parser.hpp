#pragma once
// The parser of the expression grammar (input/expression.hpp), internal to lib/input. Its
// grammar (sums, products, powers, numbers, names, interval constants) is in expression.cpp;
// its functions (calls, the functions it handles itself, and the applications that functions
// of variables become) in expression_functions.cpp.
#include "input/expression.hpp"
#include "input/expression_vocabulary.hpp"

#include <cctype>
#include <string>
#include <string_view>
#include <vector>

namespace linkbox::input::detail {

using model::Polynomial;
using expression_vocabulary::Lifted;

// Guards against inputs that would exhaust the stack or the memory instead of failing.
constexpr int kMaxNesting = 200;
constexpr size_t kMaxTermProducts = 1'000'000;

// A parsed sub-expression. `has_variable` is syntactic: "x - x" folds to 0 but still counts
// as a function of x, so sin(x - x) is rejected like sin(x).
struct Value {
  Value() = default;
  Value(Polynomial p, bool variable) : poly(std::move(p)), has_variable(variable) {}
  Polynomial poly;
  bool has_variable = false;
  std::string group;  // a parenthesised sum over two or more variables, as written (Powers)
  Interval constant() const { return poly.constant_term(); }
};

class Parser {
 public:
  // `applications`: where functions of variables go; `intervals`: where the genuine interval
  // constants are listed (null: either is an error).
  Parser(std::string_view text, const std::vector<std::string>& variables,
         std::vector<model::Application>* applications = nullptr, IntervalConstants* intervals = nullptr,
         Powers powers = Powers::expanded)
      : text_(text), variables_(variables), applications_(applications), intervals_(intervals), powers_(powers) {}

  Value parse() {
    if (next_token() == text_.size()) fail("empty expression", 0);
    Value v = expression();
    if (pos_ != text_.size()) unexpected("an operator or the end of the expression");
    return v;
  }

 private:
  // The grammar (expression.cpp).
  Value expression();
  Value term();
  Value unary();
  Value power();
  static bool is_negative_constant(const Value& e);
  Value raise(Value base, const Value& exponent, size_t base_at, size_t at, size_t exponent_at);
  Value primary();
  Value interval_constant();
  Value number();
  Value identifier();
  static bool is_half_integer(const Value& e);
  Value half_power(const Value& base, const Value& exponent, size_t base_at, size_t at, size_t exponent_at);
  Value multiply(const Value& a, const Value& b, size_t at);
  Value divide(const Value& a, const Value& b, size_t divisor_at);
  int integer_exponent(const Value& e, size_t at);
  void check_finite(const Value& v, size_t at);
  void expect_closing(size_t open_at);
  [[noreturn]] void unexpected(const std::string& expected);

  // Functions (expression_functions.cpp).
  Value call(const expression_vocabulary::Function& f, size_t name_at);
  Value special(const std::string& name, size_t name_at);
  Value extreme(const std::string& name, const Value& a, const Value& b, const std::string& text, size_t at);
  Value absolute(const Value& v, const std::string& text, size_t at);
  Value sign_of(const Value& v, const std::string& text, size_t at);
  Value angle(const Value& y, const Value& x, const std::string& text, size_t at);
  Value application(Lifted f, const Polynomial& argument, std::string text, bool raised = false,
                    const Polynomial& second = {});
  Value as_written(const Value& v, bool raised);
  Value reciprocal(const Value& divisor, size_t divisor_at);
  Value reciprocal(const Value& divisor, const std::string& text);

  [[noreturn]] void fail(const std::string& message, size_t column) {
    throw ParseError(message, static_cast<int>(column));
  }

  char peek() { return next_token() < text_.size() ? text_[pos_] : '\0'; }

  // Skips whitespace; returns the offset of the next token (text size at the end).
  size_t next_token() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    return pos_;
  }

  // Recursion depth guard: deep nesting is an error message, not a stack overflow.
  struct Nesting {
    Parser& p;
    Nesting(Parser& parser, size_t at) : p(parser) {
      if (++p.depth_ > kMaxNesting) p.fail("expression nested too deeply", at);
    }
    ~Nesting() { --p.depth_; }
  };

  std::string_view text_;
  const std::vector<std::string>& variables_;
  std::vector<model::Application>* applications_;
  IntervalConstants* intervals_;
  Powers powers_;
  size_t pos_ = 0;
  int depth_ = 0;
};

}  // namespace linkbox::input::detail
