#include "input/case_file.hpp"

#include "input/toml_reader.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

namespace linkbox::input {

namespace {

using Description = decltype(Case::description);
using Reader = Description (*)(const toml::table&, const TomlReader&);

// The one place that knows the case kinds.
const std::map<std::string, Reader>& kinds() {
  static const std::map<std::string, Reader> readers = {
      {"linkage", [](const toml::table& t, const TomlReader& r) -> Description { return read_linkage(t, r); }},
      {"polynomial", [](const toml::table& t, const TomlReader& r) -> Description { return read_polynomial(t, r); }},
      {"spherical", [](const toml::table& t, const TomlReader& r) -> Description { return read_spherical(t, r); }},
  };
  return readers;
}

}  // namespace

Case read_case_text(std::string_view text, const std::string& file) {
  toml::table root;
  try {
    root = toml::parse(text, std::string_view(file));
  } catch (const toml::parse_error& e) {
    throw InputError(file, static_cast<int>(e.source().begin.line), "TOML syntax error: " + std::string(e.description()));
  }
  const TomlReader r(file, text);
  const toml::node& kind_node = r.required(root, "kind", "case kind");
  Case c;
  c.file = file;
  c.kind = r.string(kind_node, "kind");
  c.name = r.string(r.required(root, "name", "case name"), "name");
  auto it = kinds().find(c.kind);
  if (it == kinds().end()) {
    std::string known;
    for (auto& [k, f] : kinds()) known += (known.empty() ? "" : ", ") + k;
    r.fail(kind_node, "unknown kind '" + c.kind + "' (known: " + known + ")");
  }
  c.description = it->second(root, r);
  return c;
}

Case read_case(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path, 0, "no such case file");
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, 0, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, std::string("cannot open: ") + std::strerror(errno));
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(path, 0, "read error");
  return read_case_text(text, path);
}

}  // namespace linkbox::input
