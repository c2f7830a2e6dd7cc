// The CuikSuite subset (the grammar of CuikSuite's readcuiksystem parser):
//
//   [CONSTANTS]
//   d := 20                       % one 'name := value' per definition, no ';'
//   a := 0.25
//   [SYSTEM VARS]
//   x : [-2, 2]
//   y : [-d, d]
//   [SECONDARY VARS]              % also [DUMMY VARS], [CARTESIAN VARS]
//   s : [0, 1]
//   [SYSTEM EQS]                  % also [COORD EQS], [DUMMY EQS]
//   x^2 + y^2 = 1;
//   2*x*y - a*s = 0;
//
// Every kind of variable is an unknown of the system and every equation section holds at a
// root, so roots are counted in all the variables. Equations (and inequalities, '<=' or '>=')
// are sums of signed monomials; a monomial is a product of numbers, constants, PI and
// variables, each with an optional integer power (x^2), and of SIN, COS, TAN, EXP of a
// constant or of a variable (functions of variables are lifted as in TOML cases,
// model/lifting.hpp). Constants and range bounds are expressions with + - * / ^, parentheses,
// PI, SIN COS TAN COT ASIN ACOS ATAN EXP SQRT; there a unary minus binds tighter than '^'
// (-2^2 is 4), as in CuikSuite. Keywords and section names are case-insensitive. Comments:
// '%', '#', '//' to the end of the line, '/* */'. [SEARCH] DEPTH FIRST / BREADTH FIRST is
// accepted and ignored (an order of search does not change the roots).
//
// Not supported, each an error naming it: circular ranges ('~'), INF (in a range, refused with
// a suggested bound), matrix equations (TX(...)*RZ(...) = ID), velocity and non-dynamic
// sections, [SEARCH] MIN, ATAN2, ABS, PWP, PARAMETER, DIFF, comparisons and '?:' in constants.
#include "input/cuik_file.hpp"

#include <cctype>
#include <map>
#include <set>

#include "input/peer_system.hpp"

namespace linkbox::input {

namespace {

using peer::Node;
using peer::NodePtr;
using peer::Token;


std::string upper(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return r;
}

// CuikSuite's lexer is case-insensitive: "pi", "Pi" and "PI" are all the keyword.
const std::set<std::string, std::less<>> kKeywords = {
    "DEPTH", "FIRST", "BREADTH", "MIN", "INF", "PI",   "SIN", "COS",  "TAN",       "COT",   "ACOS",
    "ASIN",  "ATAN",  "ATAN2",   "EXP", "PWP", "SQRT", "ABS", "DIFF", "PARAMETER", "PRINT",
};
// The words of matrix (transform) equations.
const std::set<std::string, std::less<>> kTransforms = {
    "TR",  "TX",    "TY",    "TZ",   "TV",   "PA",   "RX",      "RY",      "RZ",      "DRX", "DRY",
    "DRZ", "DPA_U", "DPA_V", "DDRX", "DDRY", "DDRZ", "DDPA_UU", "DDPA_UV", "DDPA_VV", "ID",  "ZE",
};
const std::map<std::string, std::string, std::less<>> kConstantFunctions = {
    {"SIN", "sin"},   {"COS", "cos"},   {"TAN", "tan"}, {"ASIN", "asin"},
    {"ACOS", "acos"}, {"ATAN", "atan"}, {"EXP", "exp"}, {"SQRT", "sqrt"},
};
// Functions a monomial may contain (of a constant or a variable).
const std::set<std::string, std::less<>> kItemFunctions = {"SIN", "COS", "TAN", "EXP"};

bool is_comparison(const Token& t) {
  static const std::set<std::string, std::less<>> ops = {"==", "!=", "<", ">", "<=", ">="};
  return t.kind == Token::Kind::Symbol && ops.count(t.text);
}

// Section order as CuikSuite's grammar has it; variable sections may repeat.
enum class Section { Constants, Variables, SystemEqs, CoordEqs, DummyEqs, Search };
struct SectionInfo {
  Section kind;
  int stage;
};
const std::map<std::string, SectionInfo, std::less<>> kSections = {
    {"CONSTANTS", {Section::Constants, 0}},
    {"SYSTEM VARS", {Section::Variables, 1}},
    {"SECONDARY VARS", {Section::Variables, 1}},
    {"DUMMY VARS", {Section::Variables, 1}},
    {"CARTESIAN VARS", {Section::Variables, 1}},
    {"SYSTEM EQS", {Section::SystemEqs, 2}},
    {"COORD EQS", {Section::CoordEqs, 3}},
    {"DUMMY EQS", {Section::DummyEqs, 4}},
    {"SEARCH", {Section::Search, 5}},
};
const std::set<std::string, std::less<>> kUnsupportedSections = {"VELOCITY VARS", "NON DYNAMIC VARS", "VELOCITY EQS",
                                                                 "NON DYNAMIC EQS"};

struct Symbol {
  bool is_constant;
  int line;
  NodePtr value;  // constants
};

class Parser {
 public:
  Parser(std::string_view text, const std::string& file)
      : t_(peer::tokenize(text, file, peer::LexerRules{true, true}), file), file_(file) {
    d_.c.format = "CuikSuite";
  }

  PeerCase parse() {
    int stage = -1;
    while (!t_.at_end()) {
      const Token& tok = t_.peek();
      if (tok.kind != Token::Kind::Section)
        t_.fail_here("expected a section such as [SYSTEM VARS], found " + peer::describe(tok));
      const Token section = t_.next();
      if (kUnsupportedSections.count(section.text))
        t_.fail(section.line, "section [" + section.text + "] is not supported (velocity and non-dynamic systems)");
      auto it = kSections.find(section.text);
      if (it == kSections.end())
        t_.fail(section.line, "unknown section [" + section.text +
                                  "] (known: [CONSTANTS], [SYSTEM VARS], [SECONDARY VARS], [DUMMY VARS], "
                                  "[CARTESIAN VARS], [SYSTEM EQS], [COORD EQS], [DUMMY EQS], [SEARCH])");
      const SectionInfo info = it->second;
      const bool repeatable = info.kind == Section::Variables;
      if (info.stage < stage || (info.stage == stage && !repeatable))
        t_.fail(section.line, "section [" + section.text +
                                  "] is out of place: the order is [CONSTANTS], the variable sections, "
                                  "[SYSTEM EQS], [COORD EQS], [DUMMY EQS], [SEARCH], each once");
      stage = info.stage;
      switch (info.kind) {
        case Section::Constants:
          constants();
          break;
        case Section::Variables:
          variables();
          break;
        case Section::Search:
          search();
          break;
        default:
          equations();
          break;
      }
    }
    const int end = t_.peek().line;
    if (d_.raw.variables.empty()) t_.fail(end, "no variables (declare them under [SYSTEM VARS])");
    if (d_.raw.equations.empty()) t_.fail(end, "no equations (write them under [SYSTEM EQS])");
    return peer::finish(std::move(d_), file_);
  }

 private:
  bool in_section_body() const { return !t_.at_end() && t_.peek().kind != Token::Kind::Section; }

  // ---- sections

  void constants() {
    while (in_section_body()) {
      if (t_.peek().kind == Token::Kind::Identifier && upper(t_.peek().text) == "PRINT") {
        t_.next();  // PRINT name only shows a value while CuikSuite reads the file
        if (t_.next().kind != Token::Kind::Identifier) t_.fail(t_.previous_line(), "expected a name after PRINT");
        continue;
      }
      const Token name = new_name("constant");
      t_.expect_symbol(":=", "':=' and the value of constant '" + name.text + "'");
      const std::string what = "constant '" + name.text + "'";
      NodePtr value = constant_expression(what);
      peer::constant_value(*value, what, file_);
      symbols_.emplace(name.text, Symbol{true, name.line, std::move(value)});
    }
  }

  void variables() {
    while (in_section_body()) {
      const Token name = new_name("variable");
      if (t_.at_symbol("~"))
        t_.fail_here("circular range ('~') of '" + name.text +
                     "' is not supported: linkbox's variables are real intervals (write ':' for one)");
      t_.expect_symbol(":", "':' and the range of variable '" + name.text + "'");
      t_.expect_symbol("[", "'[' opening the range of '" + name.text + "'");
      NodePtr lo = bound("the lower bound of '" + name.text + "'");
      t_.expect_symbol(",", "',' between the bounds of '" + name.text + "'");
      NodePtr hi = bound("the upper bound of '" + name.text + "'");
      t_.expect_symbol("]", "']' closing the range of '" + name.text + "'");
      peer::complete_unbounded(d_, name.text, lo, hi, name.line, file_);
      peer::check_variable_name(name.text, name.line, file_);
      peer::add_variable(d_, name.text, *lo, *hi, name.line, file_);
      symbols_.emplace(name.text, Symbol{false, name.line, nullptr});
    }
  }

  void equations() {
    while (in_section_body()) {
      const Token& first = t_.peek();
      if (first.kind == Token::Kind::Identifier && kTransforms.count(upper(first.text)))
        t_.fail_here("matrix equations ('TX(...)*RZ(...) = ID') are not supported");
      const std::string label = "equation " + std::to_string(++equations_);
      const int line = first.line;
      const NodePtr lhs = monomials();
      const Token op = t_.peek();
      const bool inequality = op.kind == Token::Kind::Symbol && (op.text == "<=" || op.text == ">=");
      if (!inequality && !t_.accept_symbol("="))
        t_.fail_here("expected an operator, '<=', '>=' or '=' in " + label + ", found " + peer::describe(op));
      if (inequality) t_.next();
      const NodePtr rhs = monomials();
      if (!t_.accept_symbol(";")) {
        const Token& found = t_.peek();
        if (found.line == t_.previous_line())
          t_.fail_here("expected an operator or ';' after " + label + ", found " + peer::describe(found));
        t_.fail(t_.previous_line(),
                "missing ';' after " + label + " (the next line starts with " + peer::describe(found) + ")");
      }
      if (inequality)
        peer::add_inequality(d_, lhs, op.text, rhs, line, label);
      else
        peer::add_equation(d_, lhs, rhs, line, label, file_);
    }
  }

  void search() {
    const Token& tok = t_.peek();
    const std::string word = tok.kind == Token::Kind::Identifier ? upper(tok.text) : "";
    if (word == "MIN")
      t_.fail_here("[SEARCH] MIN (minimization) is not supported: linkbox solves systems of equations");
    if ((word == "DEPTH" || word == "BREADTH") && upper(t_.peek(1).text) == "FIRST") {
      t_.next();
      t_.next();
      return;
    }
    t_.fail_here("expected DEPTH FIRST or BREADTH FIRST after [SEARCH], found " + peer::describe(tok));
  }

  // A range's end: null for an infinite one ("-INF", "+INF" or "INF").
  NodePtr bound(const std::string& what) {
    const size_t sign = t_.at_symbol("-") || t_.at_symbol("+") ? 1 : 0;
    const Token& tok = t_.peek(sign);
    if (tok.kind != Token::Kind::Identifier || upper(tok.text) != "INF" ||
        !(t_.at_symbol(",", sign + 1) || t_.at_symbol("]", sign + 1)))
      return constant_expression(what);
    for (size_t k = 0; k <= sign; ++k) t_.next();
    return nullptr;
  }

  const Token& new_name(const char* what) {
    const Token& tok = t_.peek();
    if (tok.kind != Token::Kind::Identifier)
      t_.fail_here(
          std::string("expected a ") + what +
          (std::string(what) == "constant" ? " definition ('name := value')" : " range ('name : [lower, upper]')") +
          ", found " + peer::describe(tok));
    const std::string u = upper(tok.text);
    if (kKeywords.count(u) || kTransforms.count(u))
      t_.fail_here("'" + tok.text + "' is a reserved word in .cuik files and cannot name a " + what);
    if (auto it = symbols_.find(tok.text); it != symbols_.end())
      t_.fail_here("'" + tok.text + "' is already declared on line " + std::to_string(it->second.line) + " (as a " +
                   (it->second.is_constant ? "constant" : "variable") + ")");
    return t_.next();
  }

  // ---- equations: signed monomials

  NodePtr monomials() {
    std::vector<NodePtr> terms;
    std::string ops;
    const int line = t_.peek().line;
    do {
      char sign = '+';
      if (t_.at_symbol("+") || t_.at_symbol("-")) sign = t_.next().text[0];
      const int at = t_.peek().line;
      NodePtr m = monomial();
      // The sign belongs to the monomial: "-x^2" is -(x^2).
      if (terms.empty() && sign == '-') m = peer::negate(std::move(m), at);
      terms.push_back(std::move(m));
      ops += terms.size() == 1 ? '+' : sign;
    } while (t_.at_symbol("+") || t_.at_symbol("-"));
    return peer::chain(Node::Kind::Sum, std::move(terms), std::move(ops), line);
  }

  NodePtr monomial() {
    std::vector<NodePtr> factors{item()};
    const int line = factors[0]->line;
    while (t_.accept_symbol("*")) factors.push_back(item());
    if (t_.at_symbol("/")) t_.fail_here("division is not allowed in .cuik equations (only in constants)");
    if (t_.at_symbol("(")) t_.fail_here("parentheses are not allowed in .cuik equations (only in constants)");
    return peer::chain(Node::Kind::Product, std::move(factors), std::string(factors.size(), '*'), line);
  }

  NodePtr item() {
    const Token tok = t_.next();
    NodePtr base;
    if (tok.kind == Token::Kind::Number) {
      base = peer::number(tok.text, tok.line);
    } else if (tok.kind == Token::Kind::Identifier) {
      const std::string u = upper(tok.text);
      if (u == "PI") {
        base = peer::pi(tok.line);
      } else if (kItemFunctions.count(u)) {
        base = peer::call(kConstantFunctions.at(u), item_argument(tok), tok.line);
      } else if (kTransforms.count(u)) {
        t_.fail(tok.line, "matrix equations ('TX(...)*RZ(...) = ID') are not supported");
      } else if (kKeywords.count(u)) {
        unsupported_keyword(tok, true);
      } else {
        base = name_use(tok, true);
      }
    } else if (tok.text == "(") {
      t_.fail(tok.line, "parentheses are not allowed in .cuik equations (only in constants)");
    } else {
      t_.fail(tok.line, "expected a number, a variable or a constant, found " + peer::describe(tok));
    }
    if (!t_.at_symbol("^")) return base;
    const int line = t_.next().line;
    const Token& e = t_.peek();
    if (e.kind != Token::Kind::Number || e.text.find_first_not_of("0123456789") != std::string::npos)
      t_.fail_here("'^' in a .cuik equation takes a non-negative integer, found " + peer::describe(e));
    return peer::power(std::move(base), peer::number(t_.next().text, line), line);
  }

  // SIN(x) of a variable x, or of a constant expression.
  NodePtr item_argument(const Token& function) {
    t_.expect_symbol("(", "'(' after " + function.text);
    NodePtr arg;
    const Token& first = t_.peek();
    if (first.kind == Token::Kind::Identifier && t_.at_symbol(")", 1) && is_variable(first.text))
      arg = peer::variable(t_.next().text, first.line);
    else
      arg = constant_expression("the argument of " + function.text);
    t_.expect_symbol(")", "')' closing the argument of " + function.text);
    return arg;
  }

  bool is_variable(const std::string& name) const {
    auto it = symbols_.find(name);
    return it != symbols_.end() && !it->second.is_constant;
  }

  // A declared name: a constant's value or (where allowed) a variable.
  NodePtr name_use(const Token& tok, bool variables_allowed) {
    auto it = symbols_.find(tok.text);
    if (it == symbols_.end())
      t_.fail(tok.line, "'" + tok.text + "' is not declared (neither a variable nor a constant)");
    if (it->second.is_constant) return peer::constant_use(it->second.value, tok.line);
    if (!variables_allowed)
      t_.fail(
          tok.line,
          "'" + tok.text + "' is a variable: constants, ranges and function arguments take no operations on variables");
    return peer::variable(tok.text, tok.line);
  }

  [[noreturn]] void unsupported_keyword(const Token& tok, bool in_equation) {
    const std::string u = upper(tok.text);
    if (u == "INF") t_.fail(tok.line, "INF is not supported: linkbox needs finite numbers and bounded ranges");
    if (u == "DIFF") t_.fail(tok.line, "DIFF (velocity variables) is not supported");
    if (u == "ATAN2" || u == "ABS" || u == "PWP" || u == "PARAMETER") t_.fail(tok.line, u + " is not supported");
    if (in_equation && (kConstantFunctions.count(u) || u == "COT"))
      t_.fail(tok.line,
              u + " is not allowed in a .cuik equation (only in constants; monomials take SIN, COS, TAN, EXP)");
    t_.fail(tok.line, "unexpected " + peer::describe(tok));
  }

  // ---- constant expressions: + - < * / < ^ < unary sign (CuikSuite: -2^2 is 4)

  NodePtr constant_expression(const std::string& what) {
    NodePtr e = sum();
    if (is_comparison(t_.peek())) t_.fail_here("comparisons ('" + t_.peek().text + "') are not supported in " + what);
    if (t_.at_symbol("?")) t_.fail_here("conditional expressions ('?:') are not supported in " + what);
    return e;
  }

  NodePtr sum() { return peer::sum_of(t_, [this] { return unary(); }); }

  NodePtr unary() {
    const Token tok = t_.peek();
    peer::NestingGuard guard(t_, depth_, tok.line);
    if (tok.text == "-" || tok.text == "+") {
      t_.next();
      NodePtr x = unary();
      return tok.text == "-" ? peer::negate(std::move(x), tok.line) : x;
    }
    return primary();
  }

  NodePtr primary() {
    const Token tok = t_.next();
    if (tok.kind == Token::Kind::Number) return peer::number(tok.text, tok.line);
    if (tok.kind == Token::Kind::Identifier) {
      const std::string u = upper(tok.text);
      if (u == "PI") return peer::pi(tok.line);
      if (u == "COT") {
        // CuikSuite's COT(x) is tan(pi/2 - x).
        const NodePtr x = parenthesised(tok);
        const NodePtr half_pi =
            peer::chain(Node::Kind::Product, {peer::pi(tok.line), peer::number("2", tok.line)}, "*/", tok.line);
        return peer::call("tan", peer::chain(Node::Kind::Sum, {half_pi, x}, "+-", tok.line), tok.line);
      }
      if (auto f = kConstantFunctions.find(u); f != kConstantFunctions.end())
        return peer::call(f->second, parenthesised(tok), tok.line);
      if (kKeywords.count(u) || kTransforms.count(u)) unsupported_keyword(tok, false);
      return name_use(tok, false);
    }
    if (tok.text == "(") {
      NodePtr e = sum();
      if (t_.at_symbol("?")) t_.fail_here("conditional expressions ('?:') are not supported");
      if (is_comparison(t_.peek())) t_.fail_here("comparisons ('" + t_.peek().text + "') are not supported");
      t_.expect_symbol(")", "')' closing the '(' on line " + std::to_string(tok.line));
      return e;
    }
    if (tok.kind == Token::Kind::End) t_.fail(tok.line, "the file ends inside an expression");
    t_.fail(tok.line, "expected a number, a constant or '(', found " + peer::describe(tok));
  }

  NodePtr parenthesised(const Token& function) {
    t_.expect_symbol("(", "'(' after " + function.text);
    NodePtr e = sum();
    t_.expect_symbol(")", "')' closing the argument of " + function.text);
    return e;
  }

  peer::Tokens t_;
  const std::string& file_;
  peer::Draft d_;
  std::map<std::string, Symbol, std::less<>> symbols_;
  int equations_ = 0;
  int depth_ = 0;
};

}  // namespace

PeerCase read_cuik(std::string_view text, const std::string& file) { return Parser(text, file).parse(); }

}  // namespace linkbox::input
