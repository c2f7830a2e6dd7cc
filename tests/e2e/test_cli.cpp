// The executable as a user runs it: exit codes, JSON, and `linkbox check` failing loudly on
// tampered certificates.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <unistd.h>
#include <fstream>
#include <sys/wait.h>

namespace {

int run(const std::string& args) {
  const std::string cmd = std::string(LINKBOX_CLI) + " " + args + " > /dev/null 2>&1";
  int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string src(const std::string& p) { return std::string(LINKBOX_SOURCE_DIR) + "/" + p; }

// Output files go to a fresh temporary folder, not the working directory.
std::string tmp(const std::string& name) {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("linkbox-cli-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return (dir / name).string();
}

nlohmann::json read(const std::string& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

void write(const std::string& file, const nlohmann::json& j) { std::ofstream(file) << j.dump(); }

// Solves a bundled case into `out` (exit `code`: 0 exact, 4 unresolved), requires `linkbox
// check` to accept it, returns the JSON.
nlohmann::json solved_and_checked(const std::string& case_path, const std::string& options, const std::string& out,
                                  int code = 0) {
  REQUIRE(run("solve " + src(case_path) + " --quiet " + options + " --json " + out) == code);
  REQUIRE(run("check " + out) == 0);
  return read(out);
}

// Index of the first entry of `list` with this status; list.size() when there is none.
size_t first_with_status(const nlohmann::json& list, const std::string& status) {
  size_t i = 0;
  while (i < list.size() && list[i]["status"] != status) ++i;
  return i;
}

void shift_box(nlohmann::json& box, double by) {
  for (auto& side : box) {
    side[0] = side[0].get<double>() + by;
    side[1] = side[1].get<double>() + by;
  }
}

}  // namespace

TEST_CASE("solve writes the documented JSON and check accepts it", "[cli]") {
  const std::string out = tmp("cli-wrist.json");
  REQUIRE(run("solve " + src("cases/spherical/wrist.toml") + " --quiet --json " + out) == 0);
  auto j = read(out);
  for (auto key : {"case", "variables", "parameters", "complete", "stats", "solutions", "clusters", "certified_roots", "headline"})
    CHECK(j.contains(key));
  for (auto key : {"subproblems", "processed", "empty", "split", "solution_boxes", "seconds"}) CHECK(j["stats"].contains(key));
  CHECK(j["stats"]["subproblems"] == 8);
  CHECK(j["certified_roots"] == 2);
  CHECK(j["solutions"][0]["rotation"].size() == 3);
  CHECK(run("check " + out) == 0);
}

TEST_CASE("check fails on tampered certificates", "[cli]") {
  const std::string bad = tmp("cli-tampered.json");
  const auto j = solved_and_checked("cases/spherical/agile-eye.toml", "", tmp("cli-agile.json"));
  const size_t first = first_with_status(j["clusters"], "certified");
  REQUIRE(first < j["clusters"].size());

  SECTION("a certified box shifted") {
    auto t = j;
    shift_box(t["clusters"][first]["certificate"]["box"], 1e-3);
    write(bad, t);
    CHECK(run("check " + bad) == 1);
  }
  SECTION("a reported root moved away from its certificate") {
    auto t = j;
    t["clusters"][first]["root"][0][0] = t["clusters"][first]["root"][0][0].get<double>() + 0.5;
    t["clusters"][first]["root"][0][1] = t["clusters"][first]["root"][0][1].get<double>() + 0.5;
    write(bad, t);
    CHECK(run("check " + bad) == 1);
  }
  SECTION("the root count changed") {
    auto t = j;
    t["certified_roots"] = j["certified_roots"].get<int>() + 1;
    write(bad, t);
    CHECK(run("check " + bad) == 1);
  }
  SECTION("a preconditioner zeroed") {
    auto t = j;
    for (auto& row : t["clusters"][first]["certificate"]["preconditioner"])
      for (auto& x : row) x = 0.0;
    write(bad, t);
    CHECK(run("check " + bad) == 1);
  }
  SECTION("a hull that no longer covers its boxes") {
    auto t = j;
    auto& side = t["clusters"][first]["hull"][0];
    side[1] = side[0].get<double>();
    side[0] = side[0].get<double>() - 1e-3;
    write(bad, t);
    CHECK(run("check " + bad) == 1);
  }
}

TEST_CASE("check re-runs gimbal-lock curve crossings and fails on a tampered one", "[cli]") {
  // The curve winds around a whole turn: each crossing is certified in its own chart. Its
  // map is proved (exit 0: every cluster settled).
  const std::string bad = tmp("cli-gimbal-tampered.json");
  const auto j = solved_and_checked("cases/hard/gimbal-lock.toml", "--sigma 1e-2", tmp("cli-gimbal.json"), 0);
  const size_t curve = first_with_status(j["clusters"], "curve");
  REQUIRE(curve < j["clusters"].size());
  const auto& crossings = j["clusters"][curve]["crossings"];
  const size_t first = first_with_status(crossings, "certified");
  REQUIRE(first < crossings.size());
  auto t = j;
  auto& x = t["clusters"][curve]["crossings"][first];

  SECTION("a crossing box shifted") { shift_box(x["box"], 1e-3); }
  SECTION("a crossing moved to another chart") { x["chart"] = x["chart"].get<std::uint64_t>() ^ 1; }
  SECTION("a crossing listed for a member box across the circle") {
    // phi1 at the centre of each member's box (solutions are listed by sub-problem, then index).
    const auto& members = j["clusters"][curve]["members"];
    auto phi1 = [&](size_t m) {
      size_t i = 0;
      while (j["solutions"][i]["subproblem"] != members[m][0]) ++i;
      const auto& side = j["solutions"][i + members[m][1].get<size_t>()]["box"][0];
      return 0.5 * (side[0].get<double>() + side[1].get<double>());
    };
    const double here = phi1(x["member"].get<size_t>());
    size_t across = 0;
    for (size_t m = 0; m < members.size(); ++m)
      if (std::fabs(std::remainder(phi1(m) - here, 2 * M_PI)) > std::fabs(std::remainder(phi1(across) - here, 2 * M_PI)))
        across = m;
    REQUIRE(std::fabs(std::remainder(phi1(across) - here, 2 * M_PI)) > 1);
    x["member"] = across;
  }
  write(bad, t);
  CHECK(run("check " + bad) == 1);
}

TEST_CASE("bad input exits with code 2", "[cli]") {
  CHECK(run("solve /nonexistent/case.toml") == 2);
  CHECK(run("solve " + src("cases/spherical/wrist.toml") + " --sigma -1") == 2);
  CHECK(run("solve " + src("cases/spherical/wrist.toml") + " --prune nosuch") == 2);
  CHECK(run("check /nonexistent.json") == 2);
  CHECK(run("frobnicate") == 2);
}

TEST_CASE("limits give a partial result marked incomplete", "[cli]") {
  const std::string out = tmp("cli-limited.json");
  REQUIRE(run("solve " + src("cases/spherical/four-loop.toml") + " --quiet --max-boxes 200 --json " + out) == 5);
  auto j = read(out);
  CHECK(j["complete"] == false);
  CHECK(j["stop_reason"] == "box limit reached");
  CHECK(j["headline"].get<std::string>().find("incomplete") != std::string::npos);
}

TEST_CASE("the float variant is labelled unverified and never claims an exact count", "[cli]") {
  const std::string out = tmp("cli-float.json");
  REQUIRE(run("solve " + src("cases/spherical/wrist.toml") + " --quiet --arith float --json " + out) == 4);
  auto j = read(out);
  CHECK(j["parameters"]["arith"] == "float (UNVERIFIED)");
  CHECK(j["verification"]["exact"] == false);
  CHECK(j["headline"].get<std::string>().rfind("UNVERIFIED", 0) == 0);
}
