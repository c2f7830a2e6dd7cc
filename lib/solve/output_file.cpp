#include "solve/output_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <unistd.h>

namespace linkbox::solve {

namespace fs = std::filesystem;

namespace {

// The file a path names once symbolic links are followed, a dangling link's target too
// (creating it is what the user asked for); a loop of links stops after 40.
fs::path target_of(const std::string& path) {
  fs::path p = path;
  std::error_code ec;
  for (int k = 0; k < 40 && fs::is_symlink(p, ec); ++k) {
    const fs::path to = fs::read_symlink(p, ec);
    if (ec) break;
    p = to.is_absolute() ? to : p.parent_path() / to;
  }
  return p;
}

bool special(const fs::path& p) {
  std::error_code ec;
  const fs::file_status s = fs::status(p, ec);
  return !ec && fs::exists(s) && !fs::is_regular_file(s);
}

// Writes `text` to the stream of `path` opened with `mode`; empty on success, else why.
std::string write_to(const fs::path& path, const char* mode, const std::string& text, bool sync) {
  std::FILE* f = std::fopen(path.c_str(), mode);
  if (!f) return std::strerror(errno);
  bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size() && std::fflush(f) == 0;
  if (ok && sync) ok = fsync(fileno(f)) == 0;
  const int err = errno;
  ok = std::fclose(f) == 0 && ok;
  return ok ? "" : std::strerror(err ? err : EIO);
}

fs::path temporary_beside(const fs::path& target) { return fs::path(target.string() + ".tmp"); }

// The atomic route: temporary file beside the target, flushed to the disk, then a rename.
std::string replace(const fs::path& target, const std::string& text) {
  const fs::path temp = temporary_beside(target);
  if (std::string why = write_to(temp, "wb", text, true); !why.empty()) {
    std::error_code ec;
    fs::remove(temp, ec);
    return "cannot write " + temp.string() + ": " + why;
  }
  std::error_code ec;
  fs::rename(temp, target, ec);
  if (ec) {
    fs::remove(temp, ec);
    return "cannot rename " + temp.string() + " to " + target.string() + ": " + ec.message();
  }
  return "";
}

}  // namespace

void write_output(const std::string& path, const std::string& text) {
  if (path == "-") {
    if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() || std::fflush(stdout) != 0)
      throw std::runtime_error(std::string("cannot write to standard output: ") + std::strerror(errno));
    return;
  }
  const fs::path target = target_of(path);
  std::string why = special(target) ? write_to(target, "wb", text, false) : replace(target, text);
  if (why.empty()) return;
  // In place, when only the rename failed (a read-only folder holding a writable file).
  if (!special(target) && write_to(target, "wb", text, true).empty()) return;
  const fs::path kept = fs::temp_directory_path() / ("linkbox-" + std::to_string(::getpid()) + "-" +
                                                     fs::path(path).filename().string());
  if (write_to(kept, "wb", text, true).empty())
    throw std::runtime_error(path + ": " + why + "; the output was written to " + kept.string() + " instead");
  throw std::runtime_error(path + ": " + why);
}

std::string output_problem(const std::string& path) {
  if (path.empty() || path == "-") return "";
  std::error_code ec;
  if (fs::is_directory(path, ec)) return "is a folder";
  const fs::path target = target_of(path);
  // Not opened: opening a FIFO would wait for, and then end, its reader.
  if (special(target))
    return ::access(target.c_str(), W_OK) == 0 ? "" : std::string("cannot write there (") + std::strerror(errno) + ")";
  const fs::path temp = temporary_beside(target);
  const bool temp_existed = fs::exists(temp, ec);
  if (std::FILE* f = std::fopen(temp.c_str(), "ab")) {
    std::fclose(f);
    if (!temp_existed) fs::remove(temp, ec);
    return "";
  }
  const int err = errno;
  const bool existed = fs::exists(target, ec);
  if (std::FILE* f = std::fopen(target.c_str(), "ab")) {  // the in-place fallback
    std::fclose(f);
    if (!existed) fs::remove(target, ec);
    return "";
  }
  return std::string("cannot write there (") + std::strerror(err) + ")";
}

}  // namespace linkbox::solve
