// Equations "lhs = rhs" and inequalities "lhs <= rhs" as text (input/expression.hpp): the
// comparison is found first, then each side is parsed as an expression.
#include "input/expression.hpp"

#include <cctype>

namespace linkbox::input {

namespace {

using model::Polynomial;

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// One side of a comparison, its errors placed in the whole text.
Polynomial parse_side(std::string_view text, size_t offset, const std::vector<std::string>& variables,
                      std::vector<model::Application>& applications, IntervalConstants* intervals,
                      Powers powers = Powers::expanded) {
  try {
    return parse_with_functions(text, variables, applications, intervals, powers);
  } catch (const ParseError& e) {
    throw ParseError(e.what(), e.column + static_cast<int>(offset));
  }
}

}  // namespace

model::Polynomial parse_equation(std::string_view text, const std::vector<std::string>& variables,
                                 std::vector<model::Application>& applications, IntervalConstants* intervals) {
  size_t eq = std::string_view::npos;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '<' || text[i] == '>')
      throw ParseError("a comparison in an equation: inequalities go under 'inequalities'", static_cast<int>(i));
    if (text[i] != '=') continue;
    if (eq != std::string_view::npos) throw ParseError("more than one '=' in an equation", static_cast<int>(i));
    eq = i;
  }
  if (eq == std::string_view::npos) return parse_side(text, 0, variables, applications, intervals);
  const Polynomial lhs = parse_side(text.substr(0, eq), 0, variables, applications, intervals);
  const Polynomial rhs = parse_side(text.substr(eq + 1), eq + 1, variables, applications, intervals);
  return lhs - rhs;
}

model::Inequality parse_inequality(std::string_view text, const std::vector<std::string>& variables,
                                   std::vector<model::Application>& applications, IntervalConstants* intervals,
                                   Powers powers) {
  size_t op = std::string_view::npos;
  size_t width = 1;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '=' && (i == 0 || (text[i - 1] != '<' && text[i - 1] != '>')))
      throw ParseError(i + 1 < text.size() && (text[i + 1] == '<' || text[i + 1] == '>')
                           ? "write <= or >=, not =< or =>"
                           : "'=' in an inequality (write <=, >=, < or >; equations go under 'equations')",
                       static_cast<int>(i));
    if (c != '<' && c != '>') continue;
    if (op != std::string_view::npos)
      throw ParseError("more than one comparison (write a chain a <= x <= b as two inequalities)", static_cast<int>(i));
    op = i;
    width = i + 1 < text.size() && text[i + 1] == '=' ? 2 : 1;
  }
  if (op == std::string_view::npos) throw ParseError("no comparison: an inequality needs <=, >=, < or >", 0);
  const Polynomial lhs = parse_side(text.substr(0, op), 0, variables, applications, intervals, powers);
  const Polynomial rhs = parse_side(text.substr(op + width), op + width, variables, applications, intervals, powers);
  model::Inequality c;
  c.g = text[op] == '<' ? lhs - rhs : rhs - lhs;
  c.strict = width == 1;
  c.name = std::string(trim(text));
  return c;
}

}  // namespace linkbox::input
