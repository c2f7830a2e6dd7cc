// What a user or a script reads from a run's ending: exit codes by outcome, the next command to
// try, help without parser internals, usage errors that name the mistake, and progress lines
// that agree with the summary.
#include "tests/cli_run.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

using namespace linkbox;

namespace {

using test::Ran;
using test::src;
Ran run(const std::string& args) { return test::run_cli(args); }
std::string tmp(const std::string& name) { return test::scratch(name); }
bool has(const Ran& r, const std::string& text) { return r.out.find(text) != std::string::npos; }

// Two clusters closer than the arithmetic separates, 44 solution boxes: complete, unresolved.
const std::string kUnresolved = "cases/hard/close-roots-unresolved.toml --prune hc4,lp --sigma 1e-9";

}  // namespace

TEST_CASE("exit codes tell an exact count, unresolved clusters and an incomplete search apart", "[cli]") {
  Ran r = run("solve " + src("cases/spherical/wrist.toml") + " --quiet");
  CHECK(r.code == 0);
  CHECK_FALSE(has(r, "linkbox: next:"));
  r = run("solve " + src(kUnresolved) + " --quiet");
  CHECK(r.code == 4);
  r = run("solve " + src("cases/spherical/four-loop.toml") + " --quiet --max-boxes 200");
  CHECK(r.code == 5);
  CHECK(run("solve " + src("cases/spherical/wrist.toml") + " --quiet --arith float").code == 4);
}

TEST_CASE("an incomplete or unresolved ending prints the next command to try", "[cli]") {
  const std::string cp = tmp("next.checkpoint");
  std::filesystem::remove(cp);
  Ran r = run("solve " + src("cases/spherical/four-loop.toml") + " --quiet --max-boxes 200 --checkpoint " + cp);
  CHECK(r.code == 5);
  CHECK(has(r, "linkbox: next: to go on from where it stopped: linkbox resume " + cp + "\n"));
  r = run("solve " + src("cases/spherical/four-loop.toml") + " --quiet --max-boxes 200");
  CHECK(has(r, "add --checkpoint FILE (then: linkbox resume FILE)"));
  CHECK(has(r, "--max-boxes 2000\n"));
  r = run("solve " + src(kUnresolved) + " --quiet");
  INFO(r.out);
  CHECK(has(r, "linkbox: next: inflation failed: a smaller --sigma may separate close roots"));
  CHECK(has(r, "linkbox solve " + src("cases/hard/close-roots-unresolved.toml") + " --sigma 1e-11 (with your other flags)\n"));
}

TEST_CASE("the summary points at the JSON for the boxes it leaves out only when a JSON is written", "[cli]") {
  Ran r = run("solve " + src(kUnresolved) + " --quiet");
  CHECK_FALSE(has(r, "in the JSON output"));
  CHECK(has(r, "more (--json OUT writes them all)"));
  r = run("solve " + src(kUnresolved) + " --quiet --json " + tmp("more.json"));
  CHECK(has(r, "more in the JSON output"));
}

TEST_CASE("help shows plain type names, every default and the exit codes", "[cli]") {
  const Ran r = run("help solve");
  CHECK(r.code == 0);
  CHECK_FALSE(has(r, "ENUM"));
  CHECK_FALSE(has(r, "->"));
  CHECK(has(r, "--order dfs|bfs"));
  for (auto flag : {"--sigma", "--rho", "--order", "--prune", "--bisect", "--lp", "--arith", "--time-limit", "--max-boxes",
                    "--threads", "--json", "--checkpoint", "--checkpoint-every", "--record-tree"}) {
    INFO(flag);
    const size_t at = r.out.find(std::string("  ") + flag + " ");
    REQUIRE(at != std::string::npos);
    const size_t next = r.out.find("\n  -", at + 1);
    CHECK(r.out.substr(at, next - at).find("default") != std::string::npos);
  }
  CHECK(has(r, "Exit codes: 0 complete"));
  CHECK(has(run("--help"), "Exit codes: 0 complete"));
  CHECK(has(run("help"), "Subcommands:"));
  const Ran v = run("-V");
  CHECK(v.code == 0);
  CHECK(v.out.rfind("linkbox ", 0) == 0);
}

TEST_CASE("an unknown subcommand or flag is named, with the nearest known one, exit 2", "[cli]") {
  Ran r = run("solv " + src("cases/spherical/wrist.toml"));
  CHECK(r.code == 2);
  CHECK(has(r, "unknown subcommand 'solv'; did you mean solve?"));
  r = run("--bogus");
  CHECK(r.code == 2);
  CHECK(has(r, "unknown flag --bogus"));
  r = run("solve " + src("cases/spherical/wrist.toml") + " --sigm 1e-3");
  CHECK(r.code == 2);
  CHECK(has(r, "unknown flag --sigm; did you mean --sigma?"));
  r = run("help solv");
  CHECK(r.code == 2);
  CHECK(has(r, "did you mean solve?"));
  CHECK_FALSE(has(run("frobnicate"), "A subcommand is required"));
}

TEST_CASE("progress lines count the boxes the summary reports, and the volume left never goes up", "[cli]") {
  // eco9 races two strategies for seconds: the progress counts both candidates' boxes.
  const Ran r = run("solve " + src("cases/benchmarks/eco9.bch") + " --no-verify");
  REQUIRE(r.code == 0);
  const std::regex line(R"(linkbox: \d+/\d+ sub-problems, (\d+) boxes taken, \d+ pending, <?([0-9.e+-]+)% of the volume left)");
  std::vector<long> boxes;
  std::vector<double> left;
  for (std::sregex_iterator m(r.out.begin(), r.out.end(), line), end; m != end; ++m) {
    boxes.push_back(std::stol((*m)[1]));
    left.push_back(std::stod((*m)[2]));
  }
  REQUIRE_FALSE(boxes.empty());
  for (size_t k = 1; k < left.size(); ++k) CHECK(left[k] <= left[k - 1]);
  std::smatch taken;
  REQUIRE(std::regex_search(r.out, taken, std::regex(R"(the progress lines' count: (\d+) boxes taken)")));
  CHECK(std::stol(taken[1]) >= boxes.back());
}

TEST_CASE("an incomplete result names its checkpoint, and resume of the result ends as an unbroken run", "[cli]") {
  const std::string out = tmp("limited.json"), resumed = tmp("resumed.json"), whole = tmp("whole.json");
  std::filesystem::remove(out + ".ckpt");
  Ran r = run("solve " + src("cases/spherical/four-loop.toml") + " --quiet --max-boxes 200 --json " + out);
  REQUIRE(r.code == 5);
  CHECK(has(r, "linkbox: next: to go on from where it stopped: linkbox resume " + out + "\n"));
  const nlohmann::json limited = nlohmann::json::parse(std::ifstream(out));
  REQUIRE(limited.value("checkpoint", "") == out + ".ckpt");
  REQUIRE(std::filesystem::exists(out + ".ckpt"));
  REQUIRE(run("resume " + out + " --quiet --json " + resumed).code == 0);
  REQUIRE(run("solve " + src("cases/spherical/four-loop.toml") + " --quiet --json " + whole).code == 0);
  const nlohmann::json a = nlohmann::json::parse(std::ifstream(resumed)), b = nlohmann::json::parse(std::ifstream(whole));
  CHECK(a["solutions"] == b["solutions"]);
  CHECK(a["roots"] == b["roots"]);
  CHECK(a["stats"]["processed"] == b["stats"]["processed"]);
  // A complete run keeps no checkpoint beside its result and names none.
  CHECK_FALSE(b.contains("checkpoint"));
  CHECK_FALSE(std::filesystem::exists(whole + ".ckpt"));
}

TEST_CASE("resume of a result without a checkpoint says it needs one instead of calling the file damaged", "[cli]") {
  const std::string out = tmp("limited-edited.json");
  REQUIRE(run("solve " + src("cases/spherical/four-loop.toml") + " --quiet --max-boxes 200 --json " + out).code == 5);
  nlohmann::json j = nlohmann::json::parse(std::ifstream(out));
  j.erase("checkpoint");
  std::ofstream(out) << j.dump();
  const Ran r = run("resume " + out + " --quiet");
  CHECK(r.code == 2);
  CHECK(has(r, "a result, not a checkpoint"));
  CHECK(has(r, "--checkpoint FILE"));
}
