// The polynomial format:
//
//   kind = "polynomial"
//   name = "circle-line"
//   description = "..."                                  # optional
//   variables = [ { name = "x", domain = [-2, 2] },       # or [[variables]] tables
//                 { name = "y", domain = ["-pi", "pi/2"] } ]
//   equations = [ "x^2 + y^2 - 1",                        # expression = 0, or
//                 "x^2 = y + 1",                            # lhs = rhs
//                 { name = "line", equation = "x - y" } ]
//   inequalities = [ "x >= 0",                            # optional: <=, >=, < or >
//                    { name = "clearance", inequality = "x^2 + y^2 > 0.25" } ]
//
// Numbers are TOML integers, floats (enclosed as the decimal written) or constant expression
// strings; equations and inequalities use the grammar of input/expression.hpp, with sin, cos,
// tan and sqrt of variables lifted by model::lift (model/lifting.hpp says what is accepted)
// and interval constants "[a, b]" as interval coefficients. Domains are bounded: an infinite
// bound is rejected with a suggested finite one.
#include "input/polynomial_file.hpp"

#include "input/expression.hpp"
#include "input/source_lines.hpp"
#include "input/toml_reader.hpp"
#include "input/unbounded_domain.hpp"
#include "model/lifting.hpp"

#include <array>
#include <cctype>
#include <cstdio>
#include <cmath>
#include <map>

namespace linkbox::input {

namespace {

// Whether a domain end is infinite: a float inf or the string "inf" / "infinity" (any sign).
bool is_infinite(const toml::node& e) {
  if (auto* f = e.as_floating_point()) return std::isinf(f->get());
  auto* s = e.as_string();
  if (!s) return false;
  std::string t;
  for (char c : s->get())
    if (c != ' ' && c != '+' && c != '-') t += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return t == "inf" || t == "infinity";
}

// A finite domain end as written: the string, or the number (%g).
std::string as_text(const toml::node& e) {
  if (auto* s = e.as_string()) return s->get();
  char t[32];
  if (auto* i = e.as_integer()) std::snprintf(t, sizeof t, "%lld", static_cast<long long>(i->get()));
  else if (auto* f = e.as_floating_point()) std::snprintf(t, sizeof t, "%g", f->get());
  else return "?";
  return t;
}

// A variable; an infinite end of its domain is the default bound, added to `assumed`.
model::Variable read_variable(const TomlReader& r, const toml::node& n, std::vector<std::string>& assumed) {
  const toml::table& t = r.table(n, "a variable");
  r.only_keys(t, {"name", "domain"}, "a variable");
  model::Variable v;
  v.name = r.string(r.required(t, "name", "variable name"), "variable name");
  if (!is_valid_variable_name(v.name))
    r.fail(t, "variable name '" + v.name +
                  "' is not usable in equations (letters, digits, '_', not starting with a digit; not pi, "
                  "nan, inf or a function name)");
  const std::string what = "domain of variable '" + v.name + "'";
  const toml::node& d = r.required(t, "domain", what);
  const toml::array* a = d.as_array();
  if (!a || a->size() != 2) r.numbers(d, 2, what);  // fails with the reader's message
  std::array<Interval, 2> bounds;
  std::array<std::string, 2> written;
  for (size_t k = 0; k < 2; ++k) {
    const toml::node& e = *a->get(k);
    if (is_infinite(e)) {
      bounds[k] = Interval(k == 0 ? -kDefaultBound : kDefaultBound);
    } else {
      bounds[k] = r.number(e, what);
      written[k] = as_text(e);
    }
  }
  if (is_infinite(*a->get(0)) || is_infinite(*a->get(1))) assumed.push_back(assumed_bound(v.name, written[0], written[1]));
  // Outward: the lower end of the lower bound's enclosure, the upper end of the upper one's.
  if (bounds[0].lower() > bounds[1].upper()) r.fail(d, "empty " + what + ": lower bound exceeds upper bound");
  v.domain = Interval(bounds[0].lower(), bounds[1].upper());
  return v;
}

std::vector<std::string> names_of(const model::RawSystem& s) {
  std::vector<std::string> n;
  for (auto& v : s.variables) n.push_back(v.name);
  return n;
}

// One entry of `equations` or `inequalities`: a string, or a table { name, <key> }.
template <class Parse>
void read_constraint(const TomlReader& r, const toml::node& n, const char* kind, const char* key, size_t number,
                     model::RawSystem& s, SourceLines& lines, std::string& name, Parse&& parse) {
  const toml::node* text_node = &n;
  if (auto* t = n.as_table()) {
    r.only_keys(*t, {"name", key}, std::string("an ") + kind);
    if (auto* nm = t->get("name")) name = r.string(*nm, std::string(kind) + " name");
    text_node = &r.required(*t, key, std::string(kind) + " text");
  }
  const std::string label = std::string(kind) + " " + std::to_string(number) + (name.empty() ? "" : " '" + name + "'");
  const std::string text = r.string(*text_node, label);
  try {
    const bool constant = parse(text);
    if (constant) r.fail(*text_node, label + " " + quote_text(text) + " involves no variable (it is constant)");
  } catch (const ParseError& e) {
    r.fail(*text_node,
           label + " " + quote_text(text) + ": " + e.what() + " (column " + std::to_string(e.column) + ")");
  }
  lines.place_applications(s.applications.size(), TomlReader::line_of(*text_node));
}

}  // namespace

model::System read_polynomial(const toml::table& root, const TomlReader& r) {
  r.only_keys(root, {"kind", "name", "description", "variables", "equations", "inequalities"}, "a polynomial case");
  model::RawSystem s;
  SourceLines lines;
  std::map<std::string, int> declared_on;
  const toml::array& vars = r.array(r.required(root, "variables", "variables"), "variables");
  if (vars.empty()) r.fail(vars, "no variables");
  for (auto& n : vars) {
    model::Variable v = read_variable(r, n, s.assumed_bounds);
    if (auto [it, fresh] = declared_on.emplace(v.name, TomlReader::line_of(n)); !fresh)
      r.fail(n,
             "duplicate variable '" + v.name + "' (first declared on line " + std::to_string(it->second) + ")");
    s.variables.push_back(std::move(v));
    lines.variable.push_back(TomlReader::line_of(n));
  }
  const std::vector<std::string> names = names_of(s);
  const toml::array& eqs = r.array(r.required(root, "equations", "equations"), "equations");
  if (eqs.empty()) r.fail(eqs, "no equations");
  for (size_t i = 0; i < eqs.size(); ++i) {
    std::string name;
    read_constraint(r, eqs[i], "equation", "equation", i + 1, s, lines, name, [&](const std::string& text) {
      s.equations.push_back(parse_equation(text, names, s.applications, &s.interval_constants));
      return s.equations.back().variables().empty();
    });
    s.equation_names.push_back(name);
    lines.equation.push_back(TomlReader::line_of(eqs[i]));
  }
  if (const toml::node* ineqs = root.get("inequalities")) {
    const toml::array& list = r.array(*ineqs, "inequalities");
    for (size_t i = 0; i < list.size(); ++i) {
      std::string name;
      read_constraint(r, list[i], "inequality", "inequality", i + 1, s, lines, name, [&](const std::string& text) {
        s.inequalities.push_back(parse_inequality(text, names, s.applications, &s.interval_constants));
        return s.inequalities.back().g.variables().empty();
      });
      if (!name.empty()) s.inequalities.back().name = name + ": " + s.inequalities.back().name;
      lines.inequality.push_back(TomlReader::line_of(list[i]));
    }
  }
  try {
    return model::lift(s);
  } catch (const model::LiftError& e) {
    r.fail(lines.of(e), e.what());
  }
}

model::System read_polynomial(const toml::table& root, const std::string& file, std::string_view text) {
  return read_polynomial(root, TomlReader(file, text));
}

}  // namespace linkbox::input
