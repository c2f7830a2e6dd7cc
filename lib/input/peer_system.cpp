#include "input/peer_system.hpp"

#include <algorithm>
#include <cmath>

#include "input/toml_reader.hpp"
#include "input/unbounded_domain.hpp"

namespace linkbox::input::peer {

namespace {

std::vector<std::string> names_of(const model::RawSystem& s) {
  std::vector<std::string> names;
  for (auto& v : s.variables) names.push_back(v.name);
  return names;
}

// Parses `t` with `parse`; a ParseError becomes an InputError at the line of its column.
template <class Parse>
auto parse_text(const Text& t, int line, const std::string& label, const std::string& file, Parse&& parse) {
  try {
    return parse(t.text);
  } catch (const ParseError& e) {
    throw InputError(file, t.line_at(static_cast<size_t>(e.column), line),
                     label + " (read as " + quote_text(t.text) + "): " + e.what());
  }
}

void add_parsed_inequality(Draft& d, const Draft::Comparison& q, const std::vector<std::string>& names,
                           const std::string& file) {
  Text t = write_comparison(q.lhs, q.op, q.rhs, file, q.line);
  model::Inequality c = parse_text(t, q.line, q.label, file, [&](const std::string& text) {
    return parse_inequality(text, names, d.raw.applications, &d.raw.interval_constants, Powers::as_written);
  });
  if (c.g.variables().empty()) throw InputError(file, q.line, q.label + " involves no variable (it is constant)");
  d.raw.inequalities.push_back(std::move(c));
  d.lines.inequality.push_back(q.line);
  d.lines.place_applications(d.raw.applications.size(), q.line);
  d.c.inequalities.push_back(std::move(t.text));
}

}  // namespace

Interval constant_value(const Node& n, const std::string& what, const std::string& file,
                        IntervalConstants* intervals) {
  const Text t = write(n, file, n.line);
  return parse_text(t, n.line, what, file, [&](const std::string& text) { return parse_constant(text, intervals); });
}

long integer_value(const Node& n, long min, long max, const std::string& what, const std::string& file) {
  const Interval x = constant_value(n, what, file);
  const double v = x.lower();
  if (v != x.upper() || std::floor(v) != v) throw InputError(file, n.line, what + " must be an integer");
  if (v < static_cast<double>(min) || v > static_cast<double>(max))
    throw InputError(file, n.line,
                     what + " must be between " + std::to_string(min) + " and " + std::to_string(max) + ", found " +
                         std::to_string(static_cast<long long>(v)));
  return static_cast<long>(v);
}

void add_variable(Draft& d, const std::string& name, const Node& lower, const Node& upper, int line,
                  const std::string& file) {
  const Interval lo = constant_value(lower, "lower bound of variable '" + name + "'", file);
  const Interval hi = constant_value(upper, "upper bound of variable '" + name + "'", file);
  // Outward, as for TOML domains: the lower end of the lower bound's enclosure, the upper end
  // of the upper one's.
  if (lo.lower() > hi.upper())
    throw InputError(file, line, "empty domain of variable '" + name + "': lower bound exceeds upper bound");
  d.raw.variables.push_back(model::Variable{name, Interval(lo.lower(), hi.upper())});
  d.lines.variable.push_back(line);
  d.c.bounds.push_back(PeerCase::Bounds{name, write(lower, file, line).text, write(upper, file, line).text});
}

void add_equation(Draft& d, const NodePtr& lhs, const NodePtr& rhs, int line, const std::string& label,
                  const std::string& file) {
  Text t = write_equation(lhs, rhs, file, line);
  model::Polynomial p = parse_text(t, line, label, file, [&](const std::string& text) {
    return parse_with_functions(text, names_of(d.raw), d.raw.applications, &d.raw.interval_constants,
                                Powers::as_written);
  });
  if (p.variables().empty()) throw InputError(file, line, label + " involves no variable (it is constant)");
  d.raw.equations.push_back(std::move(p));
  d.raw.equation_names.emplace_back();
  d.lines.equation.push_back(line);
  d.lines.place_applications(d.raw.applications.size(), line);
  d.c.equations.push_back(std::move(t.text));
}

void add_inequality(Draft& d, const NodePtr& lhs, const std::string& op, const NodePtr& rhs, int line,
                    const std::string& label) {
  d.inequalities.push_back(Draft::Comparison{lhs, op, rhs, line, label});
}

PeerCase finish(Draft&& d, const std::string& file) {
  const std::vector<std::string> names = names_of(d.raw);
  for (const Draft::Comparison& q : d.inequalities) add_parsed_inequality(d, q, names, file);
  try {
    d.c.system = model::lift(d.raw);
  } catch (const model::LiftError& e) {
    throw InputError(file, d.lines.of(e), e.what());
  }
  return std::move(d.c);
}

void check_variable_name(const std::string& name, int line, const std::string& file) {
  if (!is_valid_variable_name(name))
    throw InputError(file, line,
                     "variable name '" + name +
                         "' is reserved in linkbox's equations (a constant or function name there); rename it");
}

void complete_unbounded(Draft& d, const std::string& name, NodePtr& lower, NodePtr& upper, int line,
                        const std::string& file) {
  if (lower && upper) return;
  const std::string lo = lower ? write(*lower, file, line).text : "", hi = upper ? write(*upper, file, line).text : "";
  if (!lower) lower = number(std::string("-") + kDefaultBoundText, line);
  if (!upper) upper = number(kDefaultBoundText, line);
  d.raw.assumed_bounds.push_back(assumed_bound(name, lo, hi));
}

}  // namespace linkbox::input::peer
