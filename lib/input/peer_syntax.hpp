#pragma once
// Shared by the readers of the peers' formats (minibex_file, cuik_file); internal to lib/input.
//
// A peer's expression is parsed into a tree with the peer's own precedence and associativity
// (Minibex's unary minus takes a whole product, CuikSuite's binds tighter than '^'; both
// associate '^' to the left) and written back as text in linkbox's grammar
// (input/expression.hpp) with the parentheses that grammar needs to build the same tree. The
// text then goes through that grammar's parser (peer_system.hpp), so decimals are enclosed as
// written and constants are folded rigorously, exactly as in TOML cases; and the same text is
// what the converter writes, so a converted case reads back to the identical system.
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "input/input_error.hpp"

namespace linkbox::input::peer {

// ---------------------------------------------------------------------------------------
// Tokens

struct Token {
  enum class Kind { Identifier, Number, Symbol, Section, End };
  Kind kind = Kind::End;
  std::string text;  // Section: the header's words, upper-cased, single-spaced ("SYSTEM VARS")
  int line = 0;
};

struct LexerRules {
  bool percent_and_hash_comments = false;  // CuikSuite: '%' and '#' start a comment too
  bool sections = false;                   // CuikSuite: "[SYSTEM VARS]" is one token
};

// '//' and '/* */' comments always. Throws InputError on bytes no format allows.
std::vector<Token> tokenize(std::string_view text, const std::string& file, const LexerRules& rules);

// A cursor over the tokens; the last token is always End.
class Tokens {
 public:
  Tokens(std::vector<Token> tokens, std::string file) : tokens_(std::move(tokens)), file_(std::move(file)) {}

  const Token& peek(size_t ahead = 0) const;
  const Token& next();
  // The line of the last consumed token: where a missing ';' belongs.
  int previous_line() const;
  bool at_symbol(std::string_view s, size_t ahead = 0) const;
  bool at_end() const { return peek().kind == Token::Kind::End; }
  bool accept_symbol(std::string_view s);
  // Consumes the symbol or fails at the current token with "expected <what>".
  void expect_symbol(std::string_view s, const std::string& what);

  const std::string& file() const { return file_; }
  [[noreturn]] void fail(int line, const std::string& message) const { throw InputError(file_, line, message); }
  [[noreturn]] void fail_here(const std::string& message) const { fail(peek().line, message); }

 private:
  std::vector<Token> tokens_;
  size_t pos_ = 0;
  std::string file_;
};

// Deep nesting is an error message, not a stack overflow: one guard per recursion level.
class NestingGuard {
 public:
  static constexpr int kMaxNesting = 200;
  NestingGuard(const Tokens& t, int& depth, int line) : depth_(depth) {
    if (++depth_ > kMaxNesting) {
      --depth_;
      t.fail(line, "expression nested too deeply");
    }
  }
  ~NestingGuard() { --depth_; }
  NestingGuard(const NestingGuard&) = delete;
  NestingGuard& operator=(const NestingGuard&) = delete;

 private:
  int& depth_;
};

// How a token reads in a message: 'x', ';', "the end of the file", "section [SEARCH]".
std::string describe(const Token& t);

// ---------------------------------------------------------------------------------------
// Expression trees

struct Node;
using NodePtr = std::shared_ptr<const Node>;

struct Node {
  enum class Kind {
    Number,    // text: the literal as written (a decimal, never rounded)
    Variable,  // text: linkbox's name of the variable
    Pi,
    Call,      // text: linkbox's function name; args[0] (and args[1] for min and max)
    Power,     // args[0] ^ args[1]
    Negate,    // -args[0]
    Sum,       // args[0] (+|-) args[1] ...; ops[i] is the sign before args[i] ('+' for i = 0)
    Product,   // args[0] (*|/) args[1] ...; ops[i] is the operator before args[i]
    Constant,  // a use of a named constant: args[0] is its value, `line` the use
    Range,     // an interval constant [args[0], args[1]]
  };
  Kind kind;
  int line;
  std::string text;
  std::vector<NodePtr> args;
  std::string ops;
};

NodePtr number(std::string text, int line);
NodePtr variable(std::string name, int line);
NodePtr pi(int line);
NodePtr call(std::string function, NodePtr arg, int line);
NodePtr call(std::string function, std::vector<NodePtr> args, int line);  // min(a, b), max(a, b)
NodePtr power(NodePtr base, NodePtr exponent, int line);
NodePtr negate(NodePtr x, int line);
NodePtr constant_use(NodePtr value, int line);
NodePtr range(NodePtr lower, NodePtr upper, int line);
// A left-associative chain "a op b op c ..." (Sum or Product) as one node, not n nested ones;
// ops[i] is the operator before args[i] (ops[0] is '+' or '*'). One operand is returned as is.
NodePtr chain(Node::Kind kind, std::vector<NodePtr> args, std::string ops, int line);

// The binary levels both peers' grammars share, over `operand` (each reader's unary level):
// products of left-associative powers ("a^b^c" is (a^b)^c), and sums of those products.
template <class Next>
NodePtr chain_of(Tokens& t, Node::Kind kind, const char* a, const char* b, Next&& next) {
  std::vector<NodePtr> args{next()};
  std::string ops(1, *a);
  const int line = args[0]->line;
  while (t.at_symbol(a) || t.at_symbol(b)) {
    ops += t.next().text[0];
    args.push_back(next());
  }
  return chain(kind, std::move(args), std::move(ops), line);
}

template <class Operand>
NodePtr product_of(Tokens& t, Operand&& operand) {
  return chain_of(t, Node::Kind::Product, "*", "/", [&] {
    NodePtr base = operand();
    while (t.at_symbol("^")) {
      const int line = t.next().line;
      base = power(std::move(base), operand(), line);
    }
    return base;
  });
}

template <class Operand>
NodePtr sum_of(Tokens& t, Operand&& operand) {
  return chain_of(t, Node::Kind::Sum, "+", "-", [&] { return product_of(t, operand); });
}

// Whether the expression mentions a variable (a constant's value never does).
bool has_variable(const Node& n);

// Text in linkbox's grammar, with the source line of each piece: an error parse_polynomial
// reports at a column is mapped back to the line it came from.
struct Text {
  std::string text;
  std::vector<std::pair<size_t, int>> lines;  // (offset in text, source line), increasing offsets
  int line_at(size_t offset, int fallback) const;
};

// Throws InputError(file, line) when the text would exceed kMaxTextSize (constants substituted
// into constants can double the text at each level).
inline constexpr size_t kMaxTextSize = 1 << 20;
Text write(const Node& n, const std::string& file, int line);

// lhs = rhs as the text of "expression = 0": lhs alone when rhs is a literal zero.
Text write_equation(const NodePtr& lhs, const NodePtr& rhs, const std::string& file, int line);

// "lhs op rhs" for a comparison op (<=, >=, < or >).
Text write_comparison(const NodePtr& lhs, const std::string& op, const NodePtr& rhs, const std::string& file,
                      int line);

}  // namespace linkbox::input::peer
