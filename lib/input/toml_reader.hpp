#pragma once
// Typed, line-reporting access to a parsed TOML document (internal to lib/input): each
// accessor either returns what the case format requires or throws InputError at the
// offending line.
#include "input/input_error.hpp"
#include "interval/interval.hpp"

#include <toml++/toml.h>

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace linkbox::input {

class TomlReader {
 public:
  // `text` is the source toml++ parsed and must outlive the reader (it keeps views of its
  // lines); it may be empty: then float literals cannot be recovered.
  TomlReader(std::string file, std::string_view text);

  const std::string& file() const { return file_; }
  static int line_of(const toml::node& n) { return static_cast<int>(n.source().begin.line); }

  [[noreturn]] void fail(int line, const std::string& message) const;
  [[noreturn]] void fail(const toml::node& at, const std::string& message) const { fail(line_of(at), message); }

  // Rejects keys outside `allowed` (catches typos such as "equation" for "equations").
  void only_keys(const toml::table& t, std::initializer_list<std::string_view> allowed,
                 std::string_view where) const;

  // `what` names the value in messages, e.g. "'domain' of variable 'x'".
  const toml::node& required(const toml::table& t, std::string_view key, std::string_view what) const;
  std::string string(const toml::node& n, std::string_view what) const;
  bool boolean(const toml::node& n, std::string_view what) const;
  const toml::array& array(const toml::node& n, std::string_view what) const;
  const toml::table& table(const toml::node& n, std::string_view what) const;

  // A number: TOML integer, TOML float (enclosed as the decimal literal in the source) or a
  // string constant expression ("pi/2"). Always finite.
  Interval number(const toml::node& n, std::string_view what) const;
  // For a number that `number` accepts, a key equal for two numbers only when they are the
  // same real: the canonical decimal of a literal ("1.50" and "15e-1" alike), an expression
  // string as written; empty (equal to nothing) when the literal cannot be recovered. Enclosures
  // cannot say this: distinct decimals within one ulp have the same one.
  std::string exact_key(const toml::node& n) const;
  // An array of exactly `count` numbers.
  std::vector<Interval> numbers(const toml::node& n, size_t count, std::string_view what) const;

  // The `[[loops]]` tables of a mechanism: each with an optional unique `name` (default
  // "loop N") and the non-table array under `items` ("links", "factors").
  struct LoopTable {
    std::string name;
    int line;
    const toml::array* items;
  };
  std::vector<LoopTable> loops(const toml::table& root, std::string_view items) const;

 private:
  Interval float_literal(const toml::value<double>& v) const;
  std::string_view source_slice(const toml::source_region& r) const;

  std::string file_;
  std::vector<std::string_view> lines_;
};

std::string type_name(const toml::node& n);
// `text` in double quotes for a message, shortened with "..." when long.
std::string quote_text(std::string_view text);

}  // namespace linkbox::input
