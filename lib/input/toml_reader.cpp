#include "input/toml_reader.hpp"

#include "input/expression.hpp"
#include "interval/rigorous.hpp"

#include <cmath>
#include <map>

namespace linkbox::input {

namespace {

// toml++ counts columns in code points (1-based); returns the byte offset or npos.
size_t byte_offset(std::string_view line, size_t column) {
  size_t points = 0;
  for (size_t i = 0; i < line.size(); ++i) {
    if ((static_cast<unsigned char>(line[i]) & 0xC0) == 0x80) continue;  // UTF-8 continuation
    if (++points == column) return i;
  }
  return ++points == column ? line.size() : std::string_view::npos;
}

// A TOML decimal float with '_' removed: [+-] digits [. digits] [e [+-] digits].
bool is_decimal_float(std::string_view s) {
  size_t i = 0;
  auto digits = [&] {
    size_t start = i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i;
    return i > start;
  };
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  if (!digits()) return false;
  if (i < s.size() && s[i] == '.') {
    ++i;
    if (!digits()) return false;
  }
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    if (!digits()) return false;
  }
  return i == s.size();
}

// A decimal that is_decimal_float accepts as "[-]M e E", M without leading or trailing zeros
// ("0" for zero): two decimals are the same real exactly when their keys are equal.
std::string decimal_key(std::string_view s) {
  const bool negative = !s.empty() && s[0] == '-';
  size_t i = !s.empty() && (s[0] == '+' || s[0] == '-') ? 1 : 0;
  std::string m;
  long long exponent = 0;
  bool fraction = false;
  for (; i < s.size() && s[i] != 'e' && s[i] != 'E'; ++i) {
    if (s[i] == '.') {
      fraction = true;
    } else {
      m += s[i];
      exponent -= fraction ? 1 : 0;
    }
  }
  if (i < s.size()) {
    const std::string e(s.substr(i + 1));
    if (e.size() > 15) return {};
    exponent += std::stoll(e);
  }
  m.erase(0, m.find_first_not_of('0'));
  if (m.empty()) return "0";
  for (; m.back() == '0'; m.pop_back()) ++exponent;
  return (negative ? "-" : "") + m + "e" + std::to_string(exponent);
}

std::string join(std::initializer_list<std::string_view> words) {
  std::string s;
  for (auto w : words) s += (s.empty() ? "" : ", ") + std::string(w);
  return s;
}

}  // namespace

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::table:
      return "a table";
    case toml::node_type::date:
    case toml::node_type::time:
    case toml::node_type::date_time:
      return "a date/time";
    default:
      return "nothing";
  }
}

std::string quote_text(std::string_view text) {
  constexpr size_t kShown = 60;
  if (text.size() <= kShown) return "\"" + std::string(text) + "\"";
  return "\"" + std::string(text.substr(0, kShown)) + "...\"";
}

TomlReader::TomlReader(std::string file, std::string_view text) : file_(std::move(file)) {
  for (size_t start = 0; start < text.size();) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    lines_.push_back(text.substr(start, end - start));
    start = end + 1;
  }
}

void TomlReader::fail(int line, const std::string& message) const { throw InputError(file_, line, message); }

void TomlReader::only_keys(const toml::table& t, std::initializer_list<std::string_view> allowed,
                           std::string_view where) const {
  for (auto&& [key, value] : t) {
    bool known = false;
    for (auto a : allowed) known = known || key.str() == a;
    if (known) continue;
    const std::string name(key.str());
    fail(static_cast<int>(key.source().begin.line),
         "unknown key '" + name + "' in " + std::string(where) + " (allowed: " + join(allowed) + ")");
  }
}

const toml::node& TomlReader::required(const toml::table& t, std::string_view key,
                                       std::string_view what) const {
  const toml::node* n = t.get(key);
  if (!n) fail(t, "missing " + std::string(what) + " (key '" + std::string(key) + "')");
  return *n;
}

std::string TomlReader::string(const toml::node& n, std::string_view what) const {
  if (auto* s = n.as_string()) return s->get();
  fail(n, std::string(what) + " must be a string, found " + type_name(n));
}

bool TomlReader::boolean(const toml::node& n, std::string_view what) const {
  if (auto* b = n.as_boolean()) return b->get();
  fail(n, std::string(what) + " must be true or false, found " + type_name(n));
}

const toml::array& TomlReader::array(const toml::node& n, std::string_view what) const {
  if (auto* a = n.as_array()) return *a;
  fail(n, std::string(what) + " must be an array, found " + type_name(n));
}

const toml::table& TomlReader::table(const toml::node& n, std::string_view what) const {
  if (auto* t = n.as_table()) return *t;
  fail(n, std::string(what) + " must be a table, found " + type_name(n));
}

Interval TomlReader::number(const toml::node& n, std::string_view what) const {
  if (auto* i = n.as_integer()) return rigorous::decimal(std::to_string(i->get()));  // int64 may exceed 2^53
  if (auto* f = n.as_floating_point()) {
    if (!std::isfinite(f->get())) {
      const std::string_view written = source_slice(n.source());
      fail(n, std::string(what) + " must be finite, found " +
                  (written.empty() ? std::to_string(f->get()) : std::string(written)));
    }
    return float_literal(*f);
  }
  if (auto* s = n.as_string()) {
    try {
      return parse_constant(s->get());
    } catch (const ParseError& e) {
      fail(n, std::string(what) + ": " + quote_text(s->get()) + ": " + e.what() + " (column " +
                  std::to_string(e.column) + ")");
    }
  }
  fail(n, std::string(what) + " must be a number (integer, float or expression string), found " + type_name(n));
}

std::string TomlReader::exact_key(const toml::node& n) const {
  if (auto* i = n.as_integer()) return decimal_key(std::to_string(i->get()));
  if (auto* s = n.as_string()) return "expression " + s->get();
  if (auto* f = n.as_floating_point()) {
    std::string literal;
    for (char c : source_slice(f->source()))
      if (c != '_') literal += c;
    if (is_decimal_float(literal) && contains(rigorous::decimal(literal), f->get())) return decimal_key(literal);
  }
  return {};
}

std::vector<Interval> TomlReader::numbers(const toml::node& n, size_t count, std::string_view what) const {
  const toml::array* a = n.as_array();
  if (!a || a->size() != count)
    fail(n, std::string(what) + " must be an array of " + std::to_string(count) + " numbers, found " +
                (a ? "an array of " + std::to_string(a->size()) : type_name(n)));
  std::vector<Interval> r;
  for (auto& e : *a) r.push_back(number(e, what));
  return r;
}

std::vector<TomlReader::LoopTable> TomlReader::loops(const toml::table& root, std::string_view items) const {
  const toml::array& loops = array(required(root, "loops", "loops ([[loops]] tables)"), "loops");
  if (loops.empty()) fail(loops, "no loops");
  std::vector<LoopTable> out;
  std::map<std::string, int> lines;
  for (auto& n : loops) {
    const toml::table& t = table(n, "a loop");
    only_keys(t, {"name", items}, "a loop");
    LoopTable loop{t.contains("name") ? string(*t.get("name"), "loop name") : "loop " + std::to_string(out.size() + 1),
                   line_of(t), nullptr};
    if (loop.name.empty()) fail(t, "empty loop name");
    if (auto [it, fresh] = lines.emplace(loop.name, loop.line); !fresh)
      fail(t, "duplicate loop name '" + loop.name + "' (first declared on line " + std::to_string(it->second) + ")");
    const std::string what = std::string(items) + " of loop '" + loop.name + "'";
    loop.items = &array(required(t, items, what), what);
    out.push_back(std::move(loop));
  }
  return out;
}

std::string_view TomlReader::source_slice(const toml::source_region& r) const {
  if (r.begin.line != r.end.line || r.begin.line == 0 || r.begin.line > lines_.size()) return {};
  const std::string_view line = lines_[r.begin.line - 1];
  const size_t begin = byte_offset(line, r.begin.column), end = byte_offset(line, r.end.column);
  if (begin == std::string_view::npos || end == std::string_view::npos || end <= begin) return {};
  return line.substr(begin, end - begin);
}

// The user wrote a decimal; toml++ kept only the nearest double. Re-read the literal so that
// 0.0175 is enclosed as 175/10000, and cross-check that it is the literal toml++ parsed.
Interval TomlReader::float_literal(const toml::value<double>& v) const {
  std::string literal;
  for (char c : source_slice(v.source()))
    if (c != '_') literal += c;
  if (is_decimal_float(literal)) {
    const Interval x = rigorous::decimal(literal);
    if (contains(x, v.get())) return x;
  }
  // Source unavailable: the parsed double is within an ulp of the decimal.
  return Interval(std::nextafter(v.get(), -kInf), std::nextafter(v.get(), kInf));
}

}  // namespace linkbox::input
