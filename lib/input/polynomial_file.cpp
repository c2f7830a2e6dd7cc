// The polynomial format:
//
//   kind = "polynomial"
//   name = "circle-line"
//   description = "..."                                  # optional
//   variables = [ { name = "x", domain = [-2, 2] },       # or [[variables]] tables
//                 { name = "y", domain = ["-pi", "pi/2"] } ]
//   equations = [ "x^2 + y^2 - 1",                        # each means  expression = 0
//                 { name = "line", equation = "x - y" } ]
//
// Numbers are TOML integers, floats (enclosed as the decimal written) or constant expression
// strings; equations use the grammar of input/expression.hpp.
#include "input/polynomial_file.hpp"

#include "input/expression.hpp"
#include "input/toml_reader.hpp"

#include <map>

namespace linkbox::input {

namespace {

model::Variable read_variable(const TomlReader& r, const toml::node& n) {
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
  const std::vector<Interval> bounds = r.numbers(d, 2, what);
  // Outward: the lower end of the lower bound's enclosure, the upper end of the upper one's.
  if (bounds[0].lower() > bounds[1].upper()) r.fail(d, "empty " + what + ": lower bound exceeds upper bound");
  v.domain = Interval(bounds[0].lower(), bounds[1].upper());
  return v;
}

void read_equation(const TomlReader& r, const toml::node& n, size_t number, model::System& s) {
  std::string name;
  const toml::node* text_node = &n;
  if (auto* t = n.as_table()) {
    r.only_keys(*t, {"name", "equation"}, "an equation");
    if (auto* nm = t->get("name")) name = r.string(*nm, "equation name");
    text_node = &r.required(*t, "equation", "equation text");
  }
  const std::string label = "equation " + std::to_string(number) + (name.empty() ? "" : " '" + name + "'");
  const std::string text = r.string(*text_node, label);
  model::Polynomial p;
  try {
    p = parse_polynomial(text, s.names());
  } catch (const ParseError& e) {
    r.fail(*text_node,
           label + " " + quote_text(text) + ": " + e.what() + " (column " + std::to_string(e.column) + ")");
  }
  if (p.variables().empty())
    r.fail(*text_node, label + " " + quote_text(text) + " involves no variable (it is constant)");
  s.equations.push_back(std::move(p));
  s.equation_names.push_back(name);
}

}  // namespace

model::System read_polynomial(const toml::table& root, const TomlReader& r) {
  r.only_keys(root, {"kind", "name", "description", "variables", "equations"}, "a polynomial case");
  model::System s;
  std::map<std::string, int> declared_on;
  const toml::array& vars = r.array(r.required(root, "variables", "variables"), "variables");
  if (vars.empty()) r.fail(vars, "no variables");
  for (auto& n : vars) {
    model::Variable v = read_variable(r, n);
    if (auto [it, fresh] = declared_on.emplace(v.name, TomlReader::line_of(n)); !fresh)
      r.fail(n,
             "duplicate variable '" + v.name + "' (first declared on line " + std::to_string(it->second) + ")");
    s.variables.push_back(std::move(v));
  }
  const toml::array& eqs = r.array(r.required(root, "equations", "equations"), "equations");
  if (eqs.empty()) r.fail(eqs, "no equations");
  for (size_t i = 0; i < eqs.size(); ++i) read_equation(r, eqs[i], i + 1, s);
  return s;
}

model::System read_polynomial(const toml::table& root, const std::string& file, std::string_view text) {
  return read_polynomial(root, TomlReader(file, text));
}

}  // namespace linkbox::input
