// Replays every saved fuzz input through its target, in the ordinary build (no clang, no
// libFuzzer): regressions/<target>/ holds each crash or hang the fuzzer found (all fixed),
// corpus/<target>/ the minimised corpus. A target rejects bad input only with the errors the
// CLI reports as bad input (targets.hpp); anything else fails here, and under the sanitizer
// build (.ci/run) so does any memory error or undefined behaviour.
#define CATCH_CONFIG_MAIN
#include "targets.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> files_under(const fs::path& dir) {
  std::vector<fs::path> files;
  if (fs::is_directory(dir))
    for (auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file() && e.path().filename().string()[0] != '.') files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string contents(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Replays regressions/<target>/ and corpus/<target>/; returns how many inputs ran.
size_t replay(const char* name, const char* folder) {
  const auto* target = linkbox::fuzz::find_target(name);
  REQUIRE(target != nullptr);
  size_t count = 0;
  for (auto& file : files_under(fs::path(LINKBOX_FUZZ_DIR) / folder / name)) {
    INFO("input " << file.string());
    const std::string text = contents(file);
    CHECK_NOTHROW(target->run(text));
    ++count;
  }
  return count;
}

void replay_all(const char* name) {
  replay(name, "regressions");
  // The corpus is what the fuzzer kept: it must exist for every target, seeded at least.
  CHECK(replay(name, "corpus") > 0);
}

}  // namespace

TEST_CASE("fuzz inputs: TOML case reader", "[fuzz]") { replay_all("case_toml"); }
TEST_CASE("fuzz inputs: expression parser", "[fuzz]") { replay_all("expression"); }
TEST_CASE("fuzz inputs: result JSON of linkbox check", "[fuzz]") { replay_all("check_json"); }
TEST_CASE("fuzz inputs: Minibex reader", "[fuzz]") { replay_all("minibex"); }
TEST_CASE("fuzz inputs: CuikSuite reader", "[fuzz]") { replay_all("cuik"); }

TEST_CASE("fuzz targets: every target has a test above", "[fuzz]") {
  for (auto& t : linkbox::fuzz::targets())
    CHECK((std::string(t.name) == "case_toml" || std::string(t.name) == "expression" ||
           std::string(t.name) == "check_json" || std::string(t.name) == "minibex" || std::string(t.name) == "cuik"));
}
