#include "input/case_file.hpp"

#include "input/peer_case.hpp"
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

// [solve]
// sigma = 0.1         # solution box size
// rho = 0.99          # split when a shrink keeps more than this of the volume
// prune = "hc4,newton/lp"
// bisect = "widest"
// time_limit = 60     # seconds
SolveSettings read_solve_table(const toml::table& root, const TomlReader& r) {
  SolveSettings s;
  const toml::node* n = root.get("solve");
  if (!n) return s;
  const toml::table& t = r.table(*n, "the [solve] table");
  s.line = TomlReader::line_of(t);
  r.only_keys(t, {"sigma", "rho", "prune", "bisect", "time_limit"}, "the [solve] table");
  auto positive = [&](const char* key, bool zero_ok, double max) -> std::optional<double> {
    const toml::node* v = t.get(key);
    if (!v) return std::nullopt;
    const double x = r.number(*v, std::string("solve.") + key).upper();
    if (!(x > 0 || (zero_ok && x == 0)) || x > max)
      r.fail(*v, std::string("solve.") + key + " must be " + (zero_ok ? "at least 0" : "greater than 0") +
                     (max < 1e300 ? " and at most " + std::to_string(static_cast<int>(max)) : ""));
    return x;
  };
  s.sigma = positive("sigma", false, 1e308);
  s.rho = positive("rho", false, 1);
  s.time_limit = positive("time_limit", true, 1e308);
  if (auto* v = t.get("prune")) s.prune = r.string(*v, "solve.prune");
  if (auto* v = t.get("bisect")) s.bisect = r.string(*v, "solve.bisect");
  return s;
}

}  // namespace

Case read_case_text(std::string_view text, const std::string& file) {
  // The peers' formats (Minibex .bch, CuikSuite .cuik) hold polynomial systems; the extension
  // decides, as it does for the peers' own tools.
  if (const PeerReader read_peer = peer_reader_for(file)) {
    Case c;
    c.kind = "polynomial";
    c.name = peer_case_name(file);
    c.file = file;
    c.description = read_peer(text, file).system;
    return c;
  }
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
  c.solve = read_solve_table(root, r);
  root.erase("solve");  // the kinds' readers know only their own keys
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
