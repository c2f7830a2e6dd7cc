#include "input/to_toml.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "input/input_error.hpp"

namespace linkbox::input {

namespace {

// A TOML basic string. File names may hold anything; the equations are ASCII by construction.
// Bytes outside ASCII become '?' so a file name in a foreign encoding cannot make the output
// invalid UTF-8.
std::string toml_string(std::string_view s) {
  std::string r = "\"";
  for (char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      r += '\\';
      r += ch;
    } else if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04X", c);
      r += buf;
    } else {
      r += c < 0x80 ? ch : '?';
    }
  }
  return r + "\"";
}

// For comment lines: printable ASCII only.
std::string printable(std::string_view s) {
  std::string r;
  for (char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    r += c >= 0x20 && c < 0x7f ? ch : '?';
  }
  return r;
}

// A short integer reads back exactly as a TOML integer; anything else stays the expression
// text as a string, which the reader encloses as written. TOML forbids leading zeros ("09",
// found by fuzzing the Minibex reader): such a bound stays a string too.
std::string bound(const std::string& text) {
  const size_t digits = text.size() - (!text.empty() && text[0] == '-');
  const bool integer = digits > 0 && digits <= 15 &&
                       text.find_first_not_of("0123456789", text.size() - digits) == std::string::npos &&
                       (digits == 1 || text[text.size() - digits] != '0');
  return integer ? text : toml_string(text);
}

std::string file_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }

}  // namespace

std::string to_toml(const PeerCase& c, const std::string& name, const std::string& file) {
  const std::string source = printable(file_name(file));
  std::string out;
  out += "# Converted by linkbox from " + source + " (" + c.format + ").\n";
  out += "# Constants are written out where they are used and decimals as written: linkbox encloses\n";
  out += "# each decimal as the number written, so this case is as rigorous as its source.\n";
  for (auto& note : c.notes) out += "# " + printable(note) + "\n";
  out += "kind = \"polynomial\"\n";
  out += "name = " + toml_string(name) + "\n";
  out += "description = " + toml_string(source + " (" + c.format + "), converted by linkbox") + "\n";
  out += "variables = [\n";
  for (auto& b : c.bounds)
    out += "  { name = " + toml_string(b.name) + ", domain = [" + bound(b.lower) + ", " + bound(b.upper) + "] },\n";
  out += "]\n";
  out += "equations = [\n";
  for (auto& e : c.equations) out += "  " + toml_string(e) + ",\n";
  out += "]\n";
  if (c.inequalities.empty()) return out;
  out += "inequalities = [\n";
  for (auto& q : c.inequalities) out += "  " + toml_string(q) + ",\n";
  out += "]\n";
  return out;
}

std::string convert_text_to_toml(std::string_view text, const std::string& file) {
  const PeerReader read = peer_reader_for(file);
  if (!read)
    throw InputError(file, 0,
                     "convert reads Minibex (.bch) and CuikSuite (.cuik) files; this file has neither extension");
  return to_toml(read(text, file), peer_case_name(file), file);
}

std::string convert_to_toml(const std::string& path) {
  if (!peer_reader_for(path))
    throw InputError(path, 0,
                     "convert reads Minibex (.bch) and CuikSuite (.cuik) files; this file has neither extension");
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path, 0, "no such file");
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path, 0, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, std::string("cannot open: ") + std::strerror(errno));
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(path, 0, "read error");
  return convert_text_to_toml(text, path);
}

}  // namespace linkbox::input
