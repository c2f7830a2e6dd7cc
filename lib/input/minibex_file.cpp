// The Minibex subset (IbexSolve's "The Minibex Language"):
//
//   Constants                                  // optional block
//     a = 0.25;  n = 4;  f in 0;               // 'in' a number: a plain constant
//     c in [0.9, 1.1];                         // an interval constant
//     w[3] = (1; 2.5; -a);                     // a vector: its values in parentheses
//   Variables
//     x in [-1, 1];  y in [0, pi/2], v[n] in [-10, 10];   // ';' or ',' between declarations
//   Constraints
//     x^2 + sqr(y) = c;
//     v(1)*v[1] - w(2)*sin(x) = a;             // v(i) counts from 1, v[i] from 0
//     x + y <= 1;                              // also >=, < and >
//   end
//
// Expressions: numbers, pi, constants, intervals [a, b], + - * / ^ and sqr; sqrt exp ln sin
// cos tan asin acos atan sinh cosh tanh, of constants and of variables, lifted as in TOML
// cases (model/lifting.hpp), as are divisions by expressions with variables. An interval
// constant whose ends are the same number is that number; a genuine one is an interval
// coefficient wherever it is used, and is refused in domains, sizes and indices. Precedence
// and associativity are Minibex's: '^' associates to the left, and a unary minus takes the
// whole product after it. Comments: '//' and '/* */'. Each variable needs a bounded domain
// (linkbox searches a box; an unbounded one is refused with a suggested bound); the n
// components of a vector x[n] become the variables x_1 .. x_n.
//
// Not supported, each an error naming it: matrices, vector interval constants, per-component
// domains, 'Parameters', 'function', 'Minimize', 'for' loops, constraints 'in' an interval,
// other functions, vector operations, 'oo' outside domains, a system of inequalities alone.
#include "input/minibex_file.hpp"

#include <cctype>
#include <map>
#include <set>

#include "input/peer_system.hpp"
#include "input/unbounded_domain.hpp"

namespace linkbox::input {

namespace {

using peer::Node;
using peer::NodePtr;
using peer::Token;

constexpr long kMaxVectorSize = 100000;

// Minibex's function names that linkbox's grammar has, under linkbox's names.
const std::map<std::string, std::string, std::less<>> kFunctions = {
    {"sqrt", "sqrt"}, {"exp", "exp"},   {"ln", "log"},    {"sin", "sin"},   {"cos", "cos"},
    {"tan", "tan"},   {"asin", "asin"}, {"acos", "acos"}, {"atan", "atan"}, {"sinh", "sinh"},
    {"cosh", "cosh"}, {"tanh", "tanh"}, {"abs", "abs"},   {"sign", "sign"}, {"asinh", "asinh"},
    {"acosh", "acosh"}, {"atanh", "atanh"},
};
// Functions of two arguments.
const std::set<std::string, std::less<>> kBinaryFunctions = {"min", "max", "atan2"};
const std::set<std::string, std::less<>> kUnsupportedFunctions = {
    "floor", "ceil", "integer", "chi", "inf", "mid", "sup", "sum", "diff",
};
const char* const kFunctionList =
    "sqr, sqrt, exp, ln, sin, cos, tan, asin, acos, atan, atan2, sinh, cosh, tanh, asinh, acosh, atanh, abs, sign, "
    "min, max, pow";

// Block keywords are case-insensitive in Minibex ("Variables", "variables", "VARIABLES").
const std::set<std::string, std::less<>> kKeywords = {
    "constants", "variables", "parameters", "function", "minimize", "constraints",
    "return",    "begin",     "end",        "for",      "in",
};

std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

bool is_keyword(const Token& t, std::string_view keyword) {
  return t.kind == Token::Kind::Identifier && lower(t.text) == keyword;
}

bool is_reserved(const Token& t) {
  return kKeywords.count(lower(t.text)) || kFunctions.count(t.text) || kUnsupportedFunctions.count(t.text) ||
         t.text == "sqr" || t.text == "pi" || t.text == "oo";
}

struct Symbol {
  bool is_constant;
  int line;
  size_t size;                     // 0: a scalar
  std::vector<NodePtr> values;     // constants: one per component
  std::vector<std::string> names;  // variables: linkbox's name of each component
};

class Parser {
 public:
  Parser(std::string_view text, const std::string& file)
      : t_(peer::tokenize(text, file, peer::LexerRules{}), file), file_(file) {
    d_.c.format = "Minibex";
  }

  PeerCase parse() {
    if (keyword("constants")) {
      t_.next();
      constants();
    }
    if (!keyword("variables"))
      t_.fail_here("expected 'Variables', found " + peer::describe(t_.peek()) +
                   " (a Minibex system is an optional 'Constants' block, 'Variables', 'Constraints' ... 'end')");
    t_.next();
    variables();
    if (keyword("parameters")) t_.fail_here("'Parameters' blocks are not supported");
    if (keyword("function"))
      t_.fail_here("auxiliary functions ('function') are not supported; write their expressions out");
    if (keyword("minimize"))
      t_.fail_here("'Minimize' (an optimization goal) is not supported: linkbox solves systems of equations");
    if (!keyword("constraints")) t_.fail_here("expected 'Constraints', found " + peer::describe(t_.peek()));
    t_.next();
    constraints();
    if (!t_.at_end()) t_.fail_here("unexpected " + peer::describe(t_.peek()) + " after 'end'");
    return peer::finish(std::move(d_), file_);
  }

 private:
  bool keyword(std::string_view k, size_t ahead = 0) const { return is_keyword(t_.peek(ahead), k); }

  bool starts_declaration() const {
    const Token& tok = t_.peek();
    return tok.kind == Token::Kind::Identifier && !kKeywords.count(lower(tok.text));
  }

  // ---- declarations

  void constants() {
    do {
      const std::string name = declare_constant();
      if (!t_.accept_symbol(";")) missing_semicolon("the declaration of constant '" + name + "'");
    } while (starts_declaration());
  }

  void variables() {
    for (;;) {
      const std::string name = declare_variable();
      if (t_.accept_symbol(",")) continue;
      if (!t_.accept_symbol(";")) missing_semicolon("the declaration of variable '" + name + "'");
      if (!starts_declaration()) break;
    }
  }

  // A new name: an identifier that is neither reserved nor declared before.
  const Token& new_name(const char* what) {
    const Token& tok = t_.peek();
    if (tok.kind != Token::Kind::Identifier || kKeywords.count(lower(tok.text)))
      t_.fail_here(std::string("expected a ") + what + " declaration, found " + peer::describe(tok));
    if (is_reserved(tok)) t_.fail_here("'" + tok.text + "' is a reserved word and cannot name a " + what);
    if (auto it = symbols_.find(tok.text); it != symbols_.end())
      t_.fail_here("'" + tok.text + "' is already declared on line " + std::to_string(it->second.line));
    return t_.next();
  }

  // "[n]" after a name: 0 for a scalar.
  size_t dimension(const std::string& name) {
    if (!t_.accept_symbol("[")) return 0;
    const NodePtr n = constant_expression("the size of '" + name + "'");
    const long size = peer::integer_value(*n, 1, kMaxVectorSize, "the size of '" + name + "'", file_);
    t_.expect_symbol("]", "']' closing the size of '" + name + "'");
    if (t_.at_symbol("[")) t_.fail_here("matrices ('" + name + "[m][n]') are not supported, only scalars and vectors");
    return static_cast<size_t>(size);
  }

  std::string declare_constant() {
    const Token name = new_name("constant");
    const size_t size = dimension(name.text);
    if (size && keyword("in"))
      t_.fail_here("vector constant '" + name.text + "' is given 'in': only scalar interval constants are supported");
    if (!t_.at_symbol("=") && !keyword("in"))
      t_.fail_here("expected '=' or 'in' and the value of constant '" + name.text + "' (or 'Variables'), found " +
                   peer::describe(t_.peek()));
    t_.next();
    Symbol s{true, name.line, size, {}, {}};
    const std::string what = "constant '" + name.text + "'";
    if (size == 0) {
      s.values.push_back(constant_expression(what));
    } else {
      t_.expect_symbol("(", "'(' opening the " + std::to_string(size) + " values of vector " + what);
      do {
        s.values.push_back(constant_expression("component " + std::to_string(s.values.size() + 1) + " of " + what));
      } while (t_.accept_symbol(";") || t_.accept_symbol(","));
      t_.expect_symbol(")", "')' closing the values of vector " + what);
      if (s.values.size() != size)
        t_.fail(name.line, "vector " + what + " is declared with " + std::to_string(size) + " components but has " +
                               std::to_string(s.values.size()) + " values");
    }
    for (size_t i = 0; i < s.values.size(); ++i) {
      IntervalConstants intervals;
      peer::constant_value(*s.values[i], size == 0 ? what : "component " + std::to_string(i + 1) + " of " + what,
                           file_, &intervals);
      if (s.values[i]->kind == Node::Kind::Range)
        d_.c.notes.push_back("Minibex " + what + " is the interval " + peer::write(*s.values[i], file_, name.line).text +
                             ", written out where it is used.");
    }
    symbols_.emplace(name.text, std::move(s));
    return name.text;
  }

  std::string declare_variable() {
    const Token name = new_name("variable");
    const size_t size = dimension(name.text);
    if (!keyword("in") && !t_.at_symbol(";") && !t_.at_symbol(","))
      t_.fail(name.line, "expected a variable declaration ('x in [lower, upper];') or 'Constraints', found '" +
                             name.text + "' followed by " + peer::describe(t_.peek()));
    // Minibex's default domain is (-oo, +oo): null ends, completed below.
    NodePtr lo, hi;
    if (keyword("in")) {
      t_.next();
      if (t_.at_symbol("("))
        t_.fail_here("per-component domains ('in (...; ...)') are not supported: give one interval for all of '" +
                     name.text + "'");
      t_.expect_symbol("[", "'[' opening the domain of '" + name.text + "'");
      lo = bound("the lower bound of '" + name.text + "'");
      t_.expect_symbol(",", "',' between the bounds of '" + name.text + "'");
      hi = bound("the upper bound of '" + name.text + "'");
      t_.expect_symbol("]", "']' closing the domain of '" + name.text + "'");
    }
    peer::complete_unbounded(d_, name.text, lo, hi, name.line, file_);

    Symbol s{false, name.line, size, {}, {}};
    if (size == 0) {
      s.names.push_back(name.text);
    } else {
      for (size_t i = 1; i <= size; ++i) s.names.push_back(name.text + "_" + std::to_string(i));
      d_.c.notes.push_back("Minibex vector " + name.text + "[" + std::to_string(size) + "] is " + s.names.front() +
                         " .. " + s.names.back() + " (" + name.text + "(i) and " + name.text + "[i-1] in the source).");
    }
    for (size_t i = 0; i < s.names.size(); ++i) {
      const std::string& n = s.names[i];
      peer::check_variable_name(n, name.line, file_);
      const std::string origin =
          size == 0 ? "variable '" + n + "'" : "component " + std::to_string(i + 1) + " of vector '" + name.text + "'";
      auto [it, fresh] = taken_.emplace(n, origin + " (line " + std::to_string(name.line) + ")");
      if (!fresh) t_.fail(name.line, origin + " clashes with " + it->second + ": linkbox names both '" + n + "'");
      peer::add_variable(d_, n, *lo, *hi, name.line, file_);
    }
    symbols_.emplace(name.text, std::move(s));
    return name.text;
  }

  // A domain's end: null for an infinite one ("-oo", "+oo" or "oo").
  NodePtr bound(const std::string& what) {
    const size_t sign = t_.at_symbol("-") || t_.at_symbol("+") ? 1 : 0;
    const Token& tok = t_.peek(sign);
    if (tok.kind != Token::Kind::Identifier || tok.text != "oo" || !(t_.at_symbol(",", sign + 1) || t_.at_symbol("]", sign + 1)))
      return constant_expression(what);
    for (size_t k = 0; k <= sign; ++k) t_.next();
    return nullptr;
  }

  // ---- constraints

  void constraints() {
    if (keyword("end")) t_.fail_here("no constraints between 'Constraints' and 'end'");
    const int first = t_.peek().line;
    for (int number = 1;; ++number) {
      if (keyword("for")) t_.fail_here("'for' loops are not supported; write the constraints out one by one");
      if (t_.at_end()) t_.fail(t_.previous_line(), "missing 'end' after the constraints");
      constraint(number);
      const bool semicolon = t_.accept_symbol(";");
      if (keyword("end")) break;
      if (t_.at_end()) t_.fail(t_.previous_line(), "missing 'end' after the constraints");
      if (!semicolon) missing_semicolon("constraint " + std::to_string(number));
    }
    t_.next();  // end
    if (d_.raw.equations.empty())
      t_.fail(first, "every constraint is an inequality: linkbox enumerates the roots of equations (a region "
                     "defined by inequalities alone is not supported)");
  }

  void constraint(int number) {
    const std::string label = "constraint " + std::to_string(number);
    const int line = t_.peek().line;
    const NodePtr lhs = expression();
    const Token op = t_.peek();
    const bool inequality = is_inequality(op);
    if (keyword("in"))
      t_.fail_here("constraints 'in' an interval (thick equations) are not supported; write two inequalities");
    if (!inequality && !t_.accept_symbol("="))
      t_.fail_here("expected an operator, a comparison or '=' in " + label + ", found " + peer::describe(op));
    if (inequality) t_.next();
    const NodePtr rhs = expression();
    if (t_.at_symbol("=") || is_inequality(t_.peek()))
      t_.fail_here("a second comparison in " + label + " (a = b = c is not Minibex)");
    if (inequality)
      peer::add_inequality(d_, lhs, op.text, rhs, line, label);
    else
      peer::add_equation(d_, lhs, rhs, line, label, file_);
  }

  static bool is_inequality(const Token& t) {
    return t.kind == Token::Kind::Symbol && (t.text == "<=" || t.text == ">=" || t.text == "<" || t.text == ">");
  }

  [[noreturn]] void missing_semicolon(const std::string& after) {
    const Token& found = t_.peek();
    if (found.line == t_.previous_line())
      t_.fail_here("expected an operator or ';' after " + after + ", found " + peer::describe(found));
    t_.fail(t_.previous_line(),
            "missing ';' after " + after + " (the next line starts with " + peer::describe(found) + ")");
  }

  // ---- expressions (Minibex precedence: + - < * / < unary - < ^ < indexing)

  NodePtr constant_expression(const std::string& what) {
    const NodePtr e = expression();
    if (peer::has_variable(*e)) t_.fail(e->line, what + " must be a constant expression, but it uses a variable");
    return e;
  }

  NodePtr expression() { return sum(); }

  NodePtr sum() { return peer::sum_of(t_, [this] { return operand(); }); }
  NodePtr product() { return peer::product_of(t_, [this] { return operand(); }); }

  // A unary sign binds like the binary one in Minibex's grammar: "-a*b" is -(a*b) and
  // "2^-a*b" is 2^(-(a*b)).
  NodePtr operand() {
    if (t_.at_symbol("-") || t_.at_symbol("+")) {
      const Token& sign = t_.next();
      const bool minus = sign.text == "-";
      const int line = sign.line;
      peer::NestingGuard guard(t_, depth_, line);
      NodePtr x = product();
      return minus ? peer::negate(std::move(x), line) : x;
    }
    NodePtr x = primary();
    if (t_.at_symbol("'")) t_.fail_here("transposition (') is not supported");
    return x;
  }

  NodePtr primary() {
    const Token tok = t_.next();
    peer::NestingGuard guard(t_, depth_, tok.line);
    switch (tok.kind) {
      case Token::Kind::Number:
        return peer::number(tok.text, tok.line);
      case Token::Kind::Identifier:
        return identifier(tok);
      case Token::Kind::End:
        t_.fail(tok.line, "the file ends inside an expression");
      default:
        break;
    }
    if (tok.text == "(") {
      NodePtr e = expression();
      if (t_.at_symbol(",") || t_.at_symbol(";")) t_.fail_here("vector expressions ('(a, b)') are not supported");
      t_.expect_symbol(")", "')' closing the '(' on line " + std::to_string(tok.line));
      return e;
    }
    if (tok.text == "[") return interval(tok.line);
    if (tok.text == "#") t_.fail(tok.line, "hexadecimal numbers ('#...') are not supported");
    if (tok.text == "<") t_.fail(tok.line, "balls ('<mid, radius>') are not supported");
    t_.fail(tok.line, "expected a number, a name or '(', found " + peer::describe(tok));
  }

  // "[a, b]" (the '[' read): an interval constant, or a where the expression grammar takes
  // it for a point (so that it may bound a domain).
  NodePtr interval(int line) {
    const NodePtr lo = constant_expression("the lower end of an interval");
    t_.expect_symbol(",", "',' between the ends of the interval");
    const NodePtr hi = constant_expression("the upper end of an interval");
    t_.expect_symbol("]", "']' closing the '[' on line " + std::to_string(line));
    const NodePtr range = peer::range(lo, hi, line);
    IntervalConstants genuine;
    peer::constant_value(*range, "the interval", file_, &genuine);
    return genuine.empty() ? lo : range;
  }

  NodePtr identifier(const Token& tok) {
    const std::string& name = tok.text;
    if (name == "pi") return peer::pi(tok.line);
    if (name == "oo")
      t_.fail(tok.line, "infinity ('oo') is not supported: linkbox needs finite numbers and bounded domains");
    if (name == "sqr") return peer::power(argument(tok), peer::number("2", tok.line), tok.line);
    if (auto f = kFunctions.find(name); f != kFunctions.end()) return peer::call(f->second, argument(tok), tok.line);
    if (kBinaryFunctions.count(name)) {
      auto [a, b] = two_arguments(tok);
      return peer::call(name, {a, b}, tok.line);
    }
    if (name == "pow") {
      auto [base, exponent] = two_arguments(tok);
      return peer::power(base, exponent, tok.line);
    }
    if (kUnsupportedFunctions.count(name))
      t_.fail(tok.line, "function '" + name + "' is not supported (supported: " + kFunctionList + ")");
    if (kKeywords.count(lower(name))) t_.fail(tok.line, "unexpected '" + name + "' in an expression");
    auto it = symbols_.find(name);
    if (it == symbols_.end()) {
      if (t_.at_symbol("(")) t_.fail(tok.line, "unknown function '" + name + "' (supported: " + kFunctionList + ")");
      t_.fail(tok.line, "'" + name + "' is not declared (neither a variable nor a constant)");
    }
    const Symbol& s = it->second;
    size_t k = 0;
    if (s.size == 0) {
      if (t_.at_symbol("(") || t_.at_symbol("[")) t_.fail(tok.line, "'" + name + "' is a scalar and cannot be indexed");
    } else {
      k = index(s, name, tok.line);
    }
    return s.is_constant ? peer::constant_use(s.values[k], tok.line) : peer::variable(s.names[k], tok.line);
  }

  // x(i) counts from 1 (Minibex's own convention), x[i] from 0 (its older C-like one).
  size_t index(const Symbol& s, const std::string& name, int line) {
    const bool from_one = t_.at_symbol("(");
    if (!from_one && !t_.at_symbol("["))
      t_.fail(line, "vector '" + name + "' is used without an index (vector operations are not supported; write " +
                        name + "(1), " + name + "(2), ...)");
    t_.next();
    const std::string what = "the index of '" + name + "'";
    const NodePtr i = constant_expression(what);
    if (t_.at_symbol(",")) t_.fail_here("matrix indices ('" + name + "(i, j)') are not supported");
    if (t_.at_symbol(":")) t_.fail_here("index ranges ('" + name + "(i:j)') are not supported");
    t_.expect_symbol(from_one ? ")" : "]", from_one ? "')' closing the index" : "']' closing the index");
    const long v = peer::integer_value(*i, -kMaxVectorSize, kMaxVectorSize, what, file_);
    const long first = from_one ? 1 : 0;
    const long n = static_cast<long>(s.size);
    if (v < first || v >= first + n)
      t_.fail(line, "index " + std::to_string(v) + " is out of range for vector '" + name + "' of " +
                        std::to_string(n) + " components (" + name + "(1) .. " + name + "(" + std::to_string(n) +
                        "), or " + name + "[0] .. " + name + "[" + std::to_string(n - 1) + "])");
    return static_cast<size_t>(v - first);
  }

  NodePtr argument(const Token& function) {
    t_.expect_symbol("(", "'(' after '" + function.text + "'");
    NodePtr arg = expression();
    if (t_.at_symbol(",")) t_.fail_here("'" + function.text + "' takes one argument");
    t_.expect_symbol(")", "')' closing the argument of '" + function.text + "'");
    return arg;
  }

  std::pair<NodePtr, NodePtr> two_arguments(const Token& function) {
    t_.expect_symbol("(", "'(' after '" + function.text + "'");
    NodePtr a = expression();
    t_.expect_symbol(",", "',' between the two arguments of '" + function.text + "'");
    NodePtr b = expression();
    t_.expect_symbol(")", "')' closing the arguments of '" + function.text + "'");
    return {a, b};
  }

  peer::Tokens t_;
  const std::string& file_;
  peer::Draft d_;
  std::map<std::string, Symbol, std::less<>> symbols_;
  std::map<std::string, std::string> taken_;  // linkbox variable name -> where it comes from
  int depth_ = 0;
};

}  // namespace

PeerCase read_minibex(std::string_view text, const std::string& file) { return Parser(text, file).parse(); }

}  // namespace linkbox::input
