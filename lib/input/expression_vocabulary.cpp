#include "input/expression_vocabulary.hpp"

#include "interval/rigorous.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace linkbox::input::expression_vocabulary {

using model::Polynomial;

namespace {

constexpr Function kFunctions[] = {
    {"sin", rigorous::sin, true, Lifted::sin},      {"cos", rigorous::cos, true, Lifted::cos},
    {"tan", rigorous::tan, true, Lifted::tan},      {"asin", rigorous::asin, true, Lifted::asin},
    {"acos", rigorous::acos, true, Lifted::acos},   {"atan", rigorous::atan, true, Lifted::atan},
    {"sqrt", rigorous::sqrt, true, Lifted::sqrt},   {"exp", rigorous::exp, true, Lifted::exp},
    {"log", rigorous::log, true, Lifted::log},      {"sinh", rigorous::sinh, true, Lifted::sinh},
    {"cosh", rigorous::cosh, true, Lifted::cosh},   {"tanh", rigorous::tanh, true, Lifted::tanh},
    {"asinh", rigorous::asinh, true, Lifted::asinh}, {"acosh", rigorous::acosh, true, Lifted::acosh},
    {"atanh", rigorous::atanh, true, Lifted::atanh},
};

}  // namespace

const Function* find_function(std::string_view name) {
  for (auto& f : kFunctions)
    if (f.name == name) return &f;
  return nullptr;
}

int special_arity(std::string_view name) {
  if (name == "abs" || name == "sign") return 1;
  return name == "min" || name == "max" || name == "atan2" ? 2 : 0;
}

bool is_identifier_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool is_identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

bool is_nan_or_inf_name(std::string_view name) {
  std::string lower;
  for (char c : name) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower == "nan" || lower == "inf" || lower == "infinity";
}

std::string describe(char c) {
  if (std::isprint(static_cast<unsigned char>(c))) return std::string("'") + c + "'";
  char buf[16];
  std::snprintf(buf, sizeof buf, "byte 0x%02X", static_cast<unsigned char>(c));
  return buf;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

bool is_sum(const Polynomial& p) { return p.terms().size() >= 2 && p.variables().size() >= 2; }

Polynomial monomial(const model::Powers& powers) {
  Polynomial m = Polynomial::constant(Interval(1.0));
  for (auto [index, exponent] : powers) m = m * Polynomial::variable(index).pow(exponent);
  return m;
}

double exact_scale(const Polynomial& b, Polynomial& normal) {
  const Interval first = b.terms().begin()->second;
  const double c = first.lower();
  if (c != first.upper() || !(c > 0) || !std::isfinite(c) || c == 1) return 1;
  for (auto& [powers, coefficient] : b.terms()) {
    const double x = coefficient.lower(), r = x / c;
    if (x != coefficient.upper() || !std::isfinite(r) || std::fma(r, c, -x) != 0) return 1;
    normal += Polynomial::monomial(powers, Interval(r));
  }
  return c;
}

std::string shortest(double x) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, x).ptr;
  return std::string(buffer, end);
}

}  // namespace linkbox::input::expression_vocabulary
