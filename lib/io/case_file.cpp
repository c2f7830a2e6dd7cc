// Case-file entry point and the polynomial format:
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
// strings; equations use the grammar of io/expression.hpp.
#include "io/case_file.hpp"

#include "io/expression.hpp"
#include "io/linkage_file.hpp"
#include "io/toml_reader.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

namespace linkbox::io {

CaseError::CaseError(std::string file, int line, const std::string& message)
    : std::runtime_error(file + ":" + std::to_string(line) + ": " + message),
      file(std::move(file)),
      line(line),
      message(message) {}

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

std::unique_ptr<formulate::Formulation> polynomial_formulation(const toml::table& root, const TomlReader& r) {
  return std::make_unique<formulate::PolynomialFormulation>(load_polynomial(root, r));
}

// SphericalFormulation reports "file:line: message"; keep its line in our error.
std::unique_ptr<formulate::Formulation> spherical_formulation(const toml::table& root, const TomlReader& r) {
  formulate::SphericalCase c = load_spherical(root, r);
  try {
    return std::make_unique<formulate::SphericalFormulation>(std::move(c));
  } catch (const std::invalid_argument& e) {
    std::string message = e.what();
    int line = 0;
    const std::string prefix = r.file() + ":";
    if (message.rfind(prefix, 0) == 0) {
      size_t end = message.find(": ", prefix.size());
      if (end != std::string::npos) {
        try {
          line = std::stoi(message.substr(prefix.size(), end - prefix.size()));
          message = message.substr(end + 2);
        } catch (const std::exception&) {
          line = 0;
        }
      }
    }
    r.fail(line, message);
  }
}

using FormulationReader = std::unique_ptr<formulate::Formulation> (*)(const toml::table&, const TomlReader&);

// The one place that knows the case kinds.
const std::map<std::string, FormulationReader>& kinds() {
  static const std::map<std::string, FormulationReader> readers = {
      {"linkage", linkage_formulation},
      {"polynomial", polynomial_formulation},
      {"spherical", spherical_formulation},
  };
  return readers;
}

std::unique_ptr<formulate::Formulation> formulate_kind(const std::string& kind, const toml::node& kind_node,
                                                       const toml::table& root, const TomlReader& r) {
  auto it = kinds().find(kind);
  if (it == kinds().end()) {
    std::string known;
    for (auto& [k, f] : kinds()) known += (known.empty() ? "" : ", ") + k;
    r.fail(kind_node, "unknown kind '" + kind + "' (known: " + known + ")");
  }
  return it->second(root, r);
}

}  // namespace

model::System load_polynomial(const toml::table& root, const TomlReader& r) {
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

model::System load_polynomial(const toml::table& root, const std::string& file, std::string_view text) {
  return load_polynomial(root, TomlReader(file, text));
}

LoadedCase load_case_text(std::string_view text, const std::string& file) {
  try {
    toml::table root;
    try {
      root = toml::parse(text, std::string_view(file));
    } catch (const toml::parse_error& e) {
      throw CaseError(file, static_cast<int>(e.source().begin.line),
                      "TOML syntax error: " + std::string(e.description()));
    }
    const TomlReader r(file, text);
    const toml::node& kind_node = r.required(root, "kind", "case kind");
    LoadedCase c;
    c.file = file;
    c.kind = r.string(kind_node, "kind");
    c.name = r.string(r.required(root, "name", "case name"), "name");
    c.formulation = formulate_kind(c.kind, kind_node, root, r);
    return c;
  } catch (const CaseError&) {
    throw;
  } catch (const std::exception& e) {  // a bug, not the user's fault, but still no crash
    throw CaseError(file, 0, std::string("internal error while loading: ") + e.what());
  }
}

LoadedCase load_case(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw CaseError(path, 0, "no such case file");
  if (!std::filesystem::is_regular_file(path, ec)) throw CaseError(path, 0, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CaseError(path, 0, std::string("cannot open: ") + std::strerror(errno));
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw CaseError(path, 0, "read error");
  return load_case_text(text, path);
}

}  // namespace linkbox::io
