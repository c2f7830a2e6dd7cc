#include "input/peer_syntax.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>


namespace linkbox::input::peer {

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool is_identifier_char(char c) { return is_letter(c) || is_digit(c) || c == '_'; }

std::string byte_name(unsigned char c) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "byte 0x%02X", c);
  return buf;
}

// "1." and "1.e5" are numbers in Minibex; linkbox's grammar wants a digit after the point.
std::string normalized_number(std::string_view s) {
  std::string r;
  for (size_t i = 0; i < s.size(); ++i) {
    r += s[i];
    if (s[i] == '.' && (i + 1 == s.size() || !is_digit(s[i + 1]))) r += '0';
  }
  return r;
}

}  // namespace

std::vector<Token> tokenize(std::string_view text, const std::string& file, const LexerRules& rules) {
  std::vector<Token> out;
  int line = 1;
  size_t i = 0;
  auto at = [&](size_t k) { return k < text.size() ? text[k] : '\0'; };
  auto push = [&](Token::Kind kind, std::string s) { out.push_back(Token{kind, std::move(s), line}); };
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++i;
    } else if ((c == '/' && at(i + 1) == '/') || (rules.percent_and_hash_comments && (c == '%' || c == '#'))) {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (c == '/' && at(i + 1) == '*') {
      const int start = line;
      const size_t end = text.find("*/", i + 2);
      if (end == std::string_view::npos) throw InputError(file, start, "unterminated comment: '/*' without '*/'");
      for (size_t k = i; k < end; ++k) line += text[k] == '\n';
      i = end + 2;
    } else if (is_letter(c) || c == '_') {
      const size_t start = i;
      while (i < text.size() && is_identifier_char(text[i])) ++i;
      push(Token::Kind::Identifier, std::string(text.substr(start, i - start)));
    } else if (is_digit(c) || (c == '.' && is_digit(at(i + 1)))) {
      const size_t start = i;
      while (is_digit(at(i))) ++i;
      if (at(i) == '.') {
        ++i;
        while (is_digit(at(i))) ++i;
      }
      // An exponent only when digits follow: "2e" is the number 2 and then a name.
      if (at(i) == 'e' || at(i) == 'E') {
        size_t k = i + 1;
        if (at(k) == '+' || at(k) == '-') ++k;
        if (is_digit(at(k))) {
          while (is_digit(at(k))) ++k;
          i = k;
        }
      }
      push(Token::Kind::Number, normalized_number(text.substr(start, i - start)));
    } else if (rules.sections && c == '[') {
      // "[SYSTEM VARS]" is a header; "[-1, 1]" and "[a, b]" are ranges (they have a comma).
      size_t k = i + 1;
      std::string words;
      bool letters = false;
      while (k < text.size() && (is_letter(text[k]) || text[k] == ' ' || text[k] == '\t')) {
        const char w = text[k++];
        if (is_letter(w)) {
          if (!words.empty() && !letters) words += ' ';
          words += static_cast<char>(std::toupper(static_cast<unsigned char>(w)));
          letters = true;
        } else {
          letters = false;
        }
      }
      if (at(k) == ']' && !words.empty()) {
        // "[ SYSTEM VARS ]" started with a blank: drop the space it left in front.
        if (words[0] == ' ') words.erase(0, 1);
        push(Token::Kind::Section, words);
        i = k + 1;
      } else {
        push(Token::Kind::Symbol, "[");
        ++i;
      }
    } else if (static_cast<unsigned char>(c) > 0x20 && static_cast<unsigned char>(c) < 0x7f) {
      static constexpr std::string_view kPairs[] = {"<=", ">=", ":=", "==", "!="};
      std::string s(1, c);
      for (std::string_view p : kPairs)
        if (text.substr(i, 2) == p) s = std::string(p);
      push(Token::Kind::Symbol, s);
      i += s.size();
    } else {
      const auto u = static_cast<unsigned char>(c);
      throw InputError(file, line,
                       "unexpected " + byte_name(u) + (u >= 0x80 ? " (names, numbers and operators are ASCII)" : ""));
    }
  }
  // The end of a file that ends with a newline is on its last line, not the empty one after.
  const int last = line > 1 && !text.empty() && text.back() == '\n' ? line - 1 : line;
  out.push_back(Token{Token::Kind::End, "", last});
  return out;
}

const Token& Tokens::peek(size_t ahead) const { return tokens_[std::min(pos_ + ahead, tokens_.size() - 1)]; }

const Token& Tokens::next() {
  const Token& t = tokens_[pos_];
  if (pos_ + 1 < tokens_.size()) ++pos_;
  return t;
}

int Tokens::previous_line() const { return pos_ == 0 ? tokens_[0].line : tokens_[pos_ - 1].line; }

bool Tokens::at_symbol(std::string_view s, size_t ahead) const {
  const Token& t = peek(ahead);
  return t.kind == Token::Kind::Symbol && t.text == s;
}

bool Tokens::accept_symbol(std::string_view s) {
  if (!at_symbol(s)) return false;
  next();
  return true;
}

void Tokens::expect_symbol(std::string_view s, const std::string& what) {
  if (!accept_symbol(s)) fail_here("expected " + what + ", found " + describe(peek()));
}

std::string describe(const Token& t) {
  switch (t.kind) {
    case Token::Kind::End:
      return "the end of the file";
    case Token::Kind::Section:
      return "section [" + t.text + "]";
    default:
      return "'" + t.text + "'";
  }
}

// ---------------------------------------------------------------------------------------

namespace {

NodePtr make(Node::Kind kind, int line, std::string text, std::vector<NodePtr> args, std::string ops = {}) {
  return std::make_shared<const Node>(Node{kind, line, std::move(text), std::move(args), std::move(ops)});
}

}  // namespace

NodePtr number(std::string text, int line) { return make(Node::Kind::Number, line, std::move(text), {}); }
NodePtr variable(std::string name, int line) { return make(Node::Kind::Variable, line, std::move(name), {}); }
NodePtr pi(int line) { return make(Node::Kind::Pi, line, "pi", {}); }
NodePtr call(std::string function, NodePtr arg, int line) {
  return make(Node::Kind::Call, line, std::move(function), {std::move(arg)});
}
NodePtr call(std::string function, std::vector<NodePtr> args, int line) {
  return make(Node::Kind::Call, line, std::move(function), std::move(args));
}
NodePtr power(NodePtr base, NodePtr exponent, int line) {
  return make(Node::Kind::Power, line, "", {std::move(base), std::move(exponent)});
}
NodePtr negate(NodePtr x, int line) { return make(Node::Kind::Negate, line, "", {std::move(x)}); }
NodePtr constant_use(NodePtr value, int line) { return make(Node::Kind::Constant, line, "", {std::move(value)}); }
NodePtr range(NodePtr lower, NodePtr upper, int line) {
  return make(Node::Kind::Range, line, "", {std::move(lower), std::move(upper)});
}

NodePtr chain(Node::Kind kind, std::vector<NodePtr> args, std::string ops, int line) {
  if (args.size() == 1) return std::move(args[0]);
  return make(kind, line, "", std::move(args), std::move(ops));
}

bool has_variable(const Node& n) {
  if (n.kind == Node::Kind::Variable) return true;
  // Both readers refuse variables in a constant's value, and constants defined from constants
  // share their values: walking into them could take exponential time.
  if (n.kind == Node::Kind::Constant) return false;
  for (auto& a : n.args)
    if (has_variable(*a)) return true;
  return false;
}

int Text::line_at(size_t offset, int fallback) const {
  int line = fallback;
  for (auto& [at, l] : lines) {
    if (at > offset) break;
    line = l;
  }
  return line;
}

namespace {

// Binding strength in linkbox's grammar: a node written where at least `need` is required gets
// parentheses. An atom binds tightest; '^' takes atoms on both sides (its exponent is a unary
// in the grammar, but "x^-1" would read badly).
enum Strength { kAny = 0, kSum = 1, kProduct = 2, kNegate = 3, kPower = 4, kAtom = 5 };

class Writer {
 public:
  Writer(const std::string& file, int line) : file_(file), line_(line) {}

  Text take() { return Text{std::move(out_), std::move(lines_)}; }

  void put(const Node& n, int need) {
    const bool parens = strength(n) < need;
    if (parens) append("(");
    body(n);
    if (parens) append(")");
  }

 private:
  static int strength(const Node& n) {
    switch (n.kind) {
      case Node::Kind::Sum:
        return kSum;
      case Node::Kind::Product:
        return kProduct;
      case Node::Kind::Negate:
        return kNegate;
      case Node::Kind::Power:
        return kPower;
      case Node::Kind::Constant:
        return strength(*n.args[0]);
      default:
        return kAtom;
    }
  }

  void body(const Node& n) {
    switch (n.kind) {
      case Node::Kind::Number:
      case Node::Kind::Variable:
      case Node::Kind::Pi:
        mark(n.line);
        append(n.text);
        break;
      case Node::Kind::Call:
        mark(n.line);
        append(n.text);
        append("(");
        for (size_t i = 0; i < n.args.size(); ++i) {
          if (i > 0) append(", ");
          put(*n.args[i], kAny);
        }
        append(")");
        break;
      case Node::Kind::Power:
        put(*n.args[0], kAtom);
        mark(n.line);
        append("^");
        put(*n.args[1], kAtom);
        break;
      case Node::Kind::Negate:
        mark(n.line);
        append("-");
        // "-a*b" reads as (-a)*b in linkbox's grammar and -(a*b) in Minibex's; negation is
        // exact in interval arithmetic, so both give the same coefficients.
        put(*n.args[0], kProduct);
        break;
      case Node::Kind::Sum:
      case Node::Kind::Product: {
        const bool sum = n.kind == Node::Kind::Sum;
        for (size_t i = 0; i < n.args.size(); ++i) {
          const Node& a = *n.args[i];
          if (i > 0) {
            mark(a.line);
            append(sum ? (n.ops[i] == '+' ? " + " : " - ") : std::string(1, n.ops[i]));
          }
          // Later operands: a sum's terms are products ("a - (b + c)"), a product's factors are
          // powers ("a/(b*c)"); a negation later in a chain is parenthesised ("a*(-b)").
          const int need =
              i == 0 ? (sum ? kSum : kProduct) : (a.kind == Node::Kind::Negate || !sum ? kPower : kProduct);
          put(a, need);
        }
        break;
      }
      case Node::Kind::Range:
        mark(n.line);
        append("[");
        put(*n.args[0], kAny);
        append(", ");
        put(*n.args[1], kAny);
        append("]");
        break;
      case Node::Kind::Constant:
        // Errors inside a substituted constant are reported at the line that uses it.
        mark(n.line);
        ++quiet_;
        body(*n.args[0]);
        --quiet_;
        break;
    }
  }

  void mark(int line) {
    if (quiet_ == 0) lines_.emplace_back(out_.size(), line);
  }

  void append(std::string_view s) {
    out_ += s;
    if (out_.size() > kMaxTextSize)
      throw InputError(
          file_, line_,
          "expression longer than " + std::to_string(kMaxTextSize) + " characters once its constants are written out");
  }

  const std::string& file_;
  int line_;
  std::string out_;
  std::vector<std::pair<size_t, int>> lines_;
  int quiet_ = 0;
};

bool is_zero_literal(const Node& n) {
  if (n.kind == Node::Kind::Negate) return is_zero_literal(*n.args[0]);
  if (n.kind != Node::Kind::Number) return false;
  for (char c : n.text) {
    if (c == 'e' || c == 'E') break;
    if (c != '0' && c != '.') return false;
  }
  return true;
}

}  // namespace

Text write(const Node& n, const std::string& file, int line) {
  Writer w(file, line);
  w.put(n, kAny);
  return w.take();
}

Text write_equation(const NodePtr& lhs, const NodePtr& rhs, const std::string& file, int line) {
  if (is_zero_literal(*rhs)) return write(*lhs, file, line);
  const NodePtr difference = make(Node::Kind::Sum, line, "", {lhs, rhs}, "+-");
  return write(*difference, file, line);
}

Text write_comparison(const NodePtr& lhs, const std::string& op, const NodePtr& rhs, const std::string& file,
                      int line) {
  Text t = write(*lhs, file, line);
  const Text right = write(*rhs, file, line);
  t.text += " " + op + " ";
  for (auto& [at, l] : right.lines) t.lines.emplace_back(t.text.size() + at, l);
  t.text += right.text;
  return t;
}

}  // namespace linkbox::input::peer
