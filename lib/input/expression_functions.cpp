// The parser's functions (expression_parser.hpp): a call folds a constant argument and turns
// a function of variables into an application (model/lifting.hpp lifts it); abs, min, max and
// sign are written through sqrt and division, and atan2 of variables is an application of two
// arguments.
#include "input/expression_parser.hpp"

#include "interval/rigorous.hpp"

#include <algorithm>
#include <utility>

namespace linkbox::input::detail {

using namespace expression_vocabulary;

Value Parser::call(const Function& f, size_t name_at) {
  const size_t open_at = pos_++;  // at '('
  Nesting guard(*this, open_at);
  const Value arg = expression();
  expect_closing(open_at);
  if (arg.has_variable && applications_) {
    if (!f.liftable)
      fail(std::string(f.name) + " of an expression with variables: functions apply to constants only", name_at);
    if (!arg.poly.is_constant())
      return application(f.lifted, arg.poly, std::string(text_.substr(name_at, pos_ - name_at)));
    // Folded to a constant (sin(x - x)): evaluated as one below.
  } else if (arg.has_variable) {
    fail(std::string(f.name) + " of an expression with variables: functions apply to constants only", name_at);
  }
  try {
    Value r{Polynomial::constant(f.apply(arg.constant())), false};
    check_finite(r, name_at);
    return r;
  } catch (const std::domain_error& e) {
    const std::string why = e.what();
    const std::string prefix = std::string(f.name) + ":";
    fail(why.rfind(prefix, 0) == 0 ? why : prefix + " " + why, name_at);
  }
}

// The functions the parser handles itself (special_arity): their arguments, then each.
Value Parser::special(const std::string& name, size_t name_at) {
  const size_t open_at = pos_++;  // at '('
  Nesting guard(*this, open_at);
  const int arity = special_arity(name);
  std::vector<Value> args;
  for (;;) {
    args.push_back(expression());
    if (peek() != ',') break;
    if (static_cast<int>(args.size()) == arity)
      fail("'" + name + (arity == 1 ? "' takes one argument" : "' takes two arguments: " + name + "(a, b)"), pos_);
    ++pos_;
  }
  if (static_cast<int>(args.size()) < arity) fail("'" + name + "' takes two arguments: " + name + "(a, b)", pos_);
  expect_closing(open_at);
  const std::string text(text_.substr(name_at, pos_ - name_at));
  if (name == "abs") return absolute(args[0], text, name_at);
  if (name == "sign") return sign_of(args[0], text, name_at);
  if (name == "atan2") return angle(args[0], args[1], text, name_at);
  return extreme(name, args[0], args[1], text, name_at);
}

// min and max (A, B) = (A + B -+ |A - B|) / 2.
Value Parser::extreme(const std::string& name, const Value& a, const Value& b, const std::string& text, size_t at) {
  Value d{a.poly - b.poly, a.has_variable || b.has_variable};
  const Value m = absolute(d, "|difference| in " + text, at);
  Value r{(a.poly + b.poly + (name == "max" ? m.poly : -m.poly)) * Interval(0.5), d.has_variable};
  check_finite(r, at);
  return r;
}

// atan2(Y, X), the angle of the point (X, Y) in (-pi, pi]: an application of two arguments
// (model/lifting.hpp says how it is lifted). Not defined at X = Y = 0.
Value Parser::angle(const Value& y, const Value& x, const std::string& text, size_t at) {
  const bool variable = y.has_variable || x.has_variable;
  if (variable && applications_ && !(y.poly.is_constant() && x.poly.is_constant()))
    return application(Lifted::atan2, y.poly, text, false, x.poly);
  if (variable && !applications_) fail("atan2 of an expression with variables: functions apply to constants only", at);
  const Interval yc = y.constant(), xc = x.constant();
  if (zero_in(yc) && zero_in(xc)) fail("atan2(0, 0) is not defined (both arguments may be 0)", at);
  if (yc.lower() == 0 && yc.upper() == 0 && xc.upper() < 0) return Value{Polynomial::constant(rigorous::pi()), false};
  Value r{Polynomial::constant(rigorous::atan2(yc, xc)), false};
  check_finite(r, at);
  return r;
}

Value Parser::absolute(const Value& v, const std::string& text, size_t at) {
  if (!v.has_variable || v.poly.is_constant())
    return Value{Polynomial::constant(boost::numeric::abs(v.constant())), v.has_variable};
  if (!applications_)
    fail("abs, min, max and sign of an expression with variables: functions apply to constants only", at);
  return application(Lifted::sqrt, multiply(v, v, at).poly, text);
}

Value Parser::sign_of(const Value& v, const std::string& text, size_t at) {
  if (!v.has_variable || v.poly.is_constant()) {
    const Interval x = v.constant();
    const auto sign = [](double y) { return y > 0 ? 1.0 : y < 0 ? -1.0 : 0.0; };
    return Value{Polynomial::constant(Interval(sign(x.lower()), sign(x.upper()))), v.has_variable};
  }
  const Value r = absolute(v, "abs" + text.substr(4), at);
  return multiply(v, reciprocal(r, "abs" + text.substr(4)), at);
}

// The variable standing for f(argument): an equal application is reused, so sin(t) written
// twice is one unknown.
Value Parser::application(Lifted f, const Polynomial& argument, std::string text, bool raised,
                          const Polynomial& second) {
  auto& apps = *applications_;
  const auto equal = [&](const model::Application& a) {
    return a.function == f && model::same(a.argument, argument) && model::same(a.second, second);
  };
  size_t k = std::find_if(apps.begin(), apps.end(), equal) - apps.begin();
  if (k == apps.size()) apps.push_back({f, argument, std::move(text), false, second});
  apps[k].raised = apps[k].raised || raised;
  return Value{Polynomial::variable(static_cast<int>(variables_.size() + k)), true};
}

// A parenthesised sum (its group set under Powers::as_written) that is raised to a power or
// multiplied by an expression with variables, as an application (expression.hpp says why);
// model::lift expands one that is never raised.
Value Parser::as_written(const Value& v, bool raised) {
  return v.group.empty() ? v : application(Lifted::base, v.poly, v.group, raised);
}

// 1/B for a divisor with variables, as the application its text names. When B = c B',
// c > 0 its first coefficient and every coefficient of B' = B / c exact, the unknown is
// q = 1/B' (named "c/B"), so 1/(8 (1 + a)) and 1/(1 + a) are one unknown, and 1/B = q / c.
Value Parser::reciprocal(const Value& divisor, size_t divisor_at) {
  return reciprocal(divisor, std::string(trim(text_.substr(divisor_at, pos_ - divisor_at))));
}

Value Parser::reciprocal(const Value& divisor, const std::string& text) {
  const bool bare = std::all_of(text.begin(), text.end(), [](char c) { return is_identifier_char(c); }) ||
                    (text.front() == '(' && text.back() == ')');
  const std::string over = bare ? "/" + text : "/(" + text + ")";
  Polynomial normal;
  const double c = exact_scale(divisor.poly, normal);
  if (c == 1) return application(Lifted::reciprocal, divisor.poly, "1" + over);
  const Value q = application(Lifted::reciprocal, normal, shortest(c) + over);
  return Value{q.poly * (Interval(1.0) / Interval(c)), true};
}
}  // namespace linkbox::input::detail
