// Runs a user can trust: the case's [solve] settings, checkpoints and resuming, interrupts,
// output problems found before the work, and limits honoured inside an LP contraction.
#include "formulate/load.hpp"
#include "formulate/to_lph.hpp"
#include "prune/lp_relaxation.hpp"
#include "solve/search.hpp"
#include "tests/cli_run.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

using namespace linkbox;

namespace {

using test::Ran;
using test::read_json;
using test::src;
Ran run(const std::string& args) { return test::run_cli(args); }
std::string tmp(const std::string& name) { return test::scratch(name); }
nlohmann::json read(const std::string& file) { return read_json(file); }

void write(const std::string& file, const std::string& text) { std::ofstream(file) << text; }

// The result with what may differ between an unbroken and a resumed run taken out: timings,
// and where the settings came from.
nlohmann::json comparable(nlohmann::json j) {
  std::function<void(nlohmann::json&)> strip = [&](nlohmann::json& x) {
    if (x.is_object()) {
      for (const char* key : {"seconds", "cpu_seconds", "search_seconds"}) x.erase(key);
      for (auto& [k, v] : x.items()) strip(v);
    } else if (x.is_array()) {
      for (auto& v : x) strip(v);
    }
  };
  j.erase("parameters");
  strip(j);
  return j;
}

const char* kCircle = R"(kind = "polynomial"
name = "circle-line"
variables = [ { name = "x", domain = [-2, 2] }, { name = "y", domain = [-2, 2] } ]
equations = [ "x^2 + y^2 - 1", "x - y" ]
)";

}  // namespace

TEST_CASE("a case's [solve] table gives its recommended settings", "[run_control]") {
  const auto c = formulate::load_case_text(std::string(kCircle) + R"(
[solve]
sigma = 0.5
rho = 0.9
prune = "hc4,newton"
bisect = "widest"
time_limit = 30
)",
                                           "settings.toml");
  REQUIRE(c.solve.sigma);
  CHECK(*c.solve.sigma == Approx(0.5));
  CHECK(*c.solve.rho == Approx(0.9));
  CHECK(*c.solve.prune == "hc4,newton");
  CHECK(*c.solve.bisect == "widest");
  CHECK(*c.solve.time_limit == Approx(30));
  CHECK(c.solve.line == 6);
  CHECK_FALSE(formulate::load_case_text(kCircle, "plain.toml").solve.sigma);

  struct Bad {
    const char* table;
    int line;
    const char* message;
  };
  for (const Bad& bad : {Bad{"[solve]\nsigmaa = 1\n", 7, "unknown key 'sigmaa'"},
                         Bad{"[solve]\nsigma = -1\n", 7, "solve.sigma must be greater than 0"},
                         Bad{"[solve]\nrho = 2\n", 7, "solve.rho must be greater than 0 and at most 1"},
                         Bad{"[solve]\nprune = 3\n", 7, "solve.prune must be a string"},
                         Bad{"solve = 3\n", 6, "the [solve] table must be a table"}}) {
    INFO(bad.table);
    try {
      formulate::load_case_text(std::string(kCircle) + "\n" + bad.table, "bad.toml");
      FAIL("accepted");
    } catch (const input::InputError& e) {
      INFO(e.what());
      CHECK(e.line == bad.line);
      CHECK(e.message.find(bad.message) != std::string::npos);
    }
  }
}

TEST_CASE("flags override the case's settings, and the summary says where each came from", "[run_control][cli]") {
  const std::string path = tmp("settings.toml"), out = tmp("settings.json");
  write(path, std::string(kCircle) + "\n[solve]\nsigma = 0.25\nprune = \"hc4\"\n");
  Ran r = run("solve " + path + " --quiet --json " + out);
  REQUIRE(r.code == 0);
  auto j = read(out);
  CHECK(j["parameters"]["sigma"] == 0.25);
  CHECK(j["parameters"]["prune"] == "hc4");
  CHECK(j["parameters"]["sources"]["sigma"] == "case file");
  CHECK_FALSE(j["parameters"]["sources"].contains("rho"));
  CHECK(r.out.find("sigma (case file)") != std::string::npos);

  REQUIRE(run("solve " + path + " --quiet --sigma 0.125 --json " + out).code == 0);
  j = read(out);
  CHECK(j["parameters"]["sigma"] == 0.125);
  CHECK(j["parameters"]["sources"]["sigma"] == "flag");
  CHECK(j["parameters"]["prune"] == "hc4");

  // A setting the solver does not know is bad input at the table's line.
  write(path, std::string(kCircle) + "\n[solve]\nprune = \"hc5\"\n");
  r = run("solve " + path + " --quiet");
  CHECK(r.code == 2);
  CHECK(r.out.find(path + ":6: [solve] prune: unknown pruning strategy 'hc5'") != std::string::npos);
}

TEST_CASE("rho without a setting: the papers' 0.99 on spherical cases, 0.8 elsewhere, and a flag wins", "[run_control][cli]") {
  const std::string path = tmp("rho.toml"), out = tmp("rho.json");
  write(path, kCircle);
  Ran r = run("solve " + path + " --json " + out + " --quiet");
  REQUIRE(r.code == 0);
  CHECK(read(out)["parameters"]["rho"] == solve::kAutoRho);
  CHECK(r.out.find("rho=auto (0.8)") != std::string::npos);
  REQUIRE(run("solve " + src("cases/spherical/wrist.toml") + " --json " + out + " --quiet").code == 0);
  CHECK(read(out)["parameters"]["rho"] == solve::kPapersRho);
  r = run("solve " + path + " --rho 0.95 --json " + out + " --quiet");
  REQUIRE(r.code == 0);
  CHECK(read(out)["parameters"]["rho"] == 0.95);
  CHECK(r.out.find("rho=0.95") != std::string::npos);
  // One thread: the process's CPU time during the search cannot exceed its wall time (a sum
  // of wall times read as CPU could); rusage ticks leave a little slack.
  const auto stats = read(out)["stats"];
  CHECK(stats["cpu_seconds"].get<double>() >= 0);
  CHECK(stats["cpu_seconds"].get<double>() <= stats["seconds"].get<double>() + 0.02);
  CHECK(stats.contains("search_seconds"));
}

TEST_CASE("output problems are bad input, reported before the search", "[run_control][cli]") {
  Ran r = run("solve " + src("cases/spherical/wrist.toml") + " --quiet --json /nonexistent-dir/x.json");
  CHECK(r.code == 2);
  CHECK(r.out.find("--json /nonexistent-dir/x.json: cannot write there") != std::string::npos);
  CHECK(r.out.find("verification") == std::string::npos);  // nothing was solved
  r = run("solve " + src("cases/spherical/wrist.toml") + " --quiet --checkpoint " +
          std::filesystem::temp_directory_path().string());
  CHECK(r.code == 2);
  CHECK(r.out.find("is a folder") != std::string::npos);
  r = run("solve " + src("cases/spherical/wrist.toml") + " --sigma -1");
  CHECK(r.code == 2);
  CHECK(r.out.find("expected a number > 0, got '-1'") != std::string::npos);
  CHECK(r.out.find("e+308") == std::string::npos);
  r = run("--version");
  CHECK(r.code == 0);
  CHECK(r.out.rfind("linkbox ", 0) == 0);
}

TEST_CASE("each subcommand's --help shows examples of itself", "[run_control][cli]") {
  for (const std::string sub : {"solve", "resume", "check", "convert"}) {
    INFO(sub);
    const Ran r = run(sub + " --help");
    CHECK(r.code == 0);
    const size_t examples = r.out.find("Examples:");
    REQUIRE(examples != std::string::npos);
    CHECK(r.out.find("linkbox " + sub + " ", examples) != std::string::npos);
  }
}

TEST_CASE("a run stopped by a limit and resumed from its checkpoint ends with the boxes of an unbroken run",
          "[run_control][cli][slow]") {
  struct Case {
    const char* path;
    const char* stop;
    const char* resume;
    bool raced;  // stopped while its candidates race
  };
  // A raced linkage (both candidates mid-way), and a spherical case of many sub-problems on
  // two threads (some finished, some under way, some not started).
  for (const Case& c : {Case{"cases/linkages/6r-rigid.toml", "--max-boxes 700", "", true},
                        Case{"cases/spherical/four-loop.toml", "--max-boxes 3000 --threads 2", "--threads 2", false}}) {
    INFO(c.path);
    const std::string whole = tmp("whole.json"), part = tmp("part.json"), resumed = tmp("resumed.json"),
                      cp = tmp("run.checkpoint");
    std::filesystem::remove(cp);
    REQUIRE(run("solve " + src(c.path) + " --quiet --json " + whole).code == 0);
    REQUIRE(run("solve " + src(c.path) + " --quiet " + c.stop + " --checkpoint " + cp + " --json " + part).code == 5);
    const auto p = read(part);
    REQUIRE(p["complete"] == false);
    CHECK(p["pending_boxes"].get<long>() > 0);
    CHECK(p["volume_left"].get<double>() > 0);
    CHECK(p["volume_left"].get<double>() <= 1);
    // A race's lead rule reads each candidate's past progress: the checkpoint keeps it.
    bool raced = false;
    const auto checkpoint = read(cp);
    for (auto& sub : checkpoint.at("subproblems")) {
      if (sub.at("phase") != "searching" || sub.at("searches").size() < 2) continue;
      const auto& race = sub.at("race");
      if (race.at("choices").empty()) continue;
      raced = true;
      REQUIRE(race.at("progress").size() == sub.at("searches").size());
      for (auto& points : race.at("progress")) CHECK(points.size() == race.at("choices").size());
    }
    CHECK(raced == c.raced);
    REQUIRE(run("resume " + cp + " --quiet " + c.resume + " --json " + resumed).code == 0);
    const auto w = read(whole), r = read(resumed);
    CHECK(r["complete"] == true);
    CHECK(r["parameters"]["sources"]["sigma"] == "checkpoint");
    CHECK(comparable(r) == comparable(w));
  }
}

TEST_CASE("a checkpoint of another case, of other settings or damaged is refused", "[run_control][cli]") {
  const std::string cp = tmp("refuse.checkpoint");
  std::filesystem::remove(cp);
  REQUIRE(run("solve " + src("cases/spherical/wrist.toml") + " --quiet --max-boxes 5 --checkpoint " + cp).code == 5);
  Ran r = run("resume " + cp + " --quiet --sigma 0.001");
  CHECK(r.code == 2);
  CHECK(r.out.find("the checkpoint was made with sigma 0.0001, not 0.001") != std::string::npos);
  r = run("resume " + cp + " --quiet --case " + src("cases/spherical/agile-eye.toml"));
  CHECK(r.code == 2);
  CHECK(r.out.find("was made for another case") != std::string::npos);
  write(cp + ".bad", "{\"linkbox_checkpoint\": 2, \"header\": {}, \"subproblems\": [{\"phase\": \"dreaming\"}]}");
  r = run("resume " + cp + ".bad --quiet --case " + src("cases/spherical/wrist.toml"));
  CHECK(r.code == 2);
  write(cp + ".bad", "{");
  r = run("resume " + cp + ".bad --quiet");
  CHECK(r.code == 2);
  CHECK(r.out.find("is damaged") != std::string::npos);
  CHECK(run("resume " + cp + " --quiet --sigma 0.0001").code == 0);  // the same settings are fine
}

TEST_CASE("an interrupt keeps what was proven: partial JSON, pending boxes, exit 128 + signal, how to resume",
          "[run_control][cli]") {
  const std::string out = tmp("interrupted.json"), cp = tmp("interrupted.checkpoint"), err = tmp("interrupted.err");
  std::filesystem::remove(cp);
  std::filesystem::remove(out);
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    // eco9 takes seconds; the checkpoint file appears when the search has started.
    if (!std::freopen(err.c_str(), "w", stderr)) _exit(126);
    execl(LINKBOX_CLI, LINKBOX_CLI, "solve", src("cases/benchmarks/eco9.toml").c_str(), "--quiet", "--json",
          out.c_str(), "--checkpoint", cp.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  for (int i = 0; i < 6000 && !std::filesystem::exists(cp); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  REQUIRE(std::filesystem::exists(cp));
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 128 + SIGINT);
  const auto j = read(out);
  CHECK(j["complete"] == false);
  CHECK(j["stop_reason"] == "interrupted");
  CHECK(j["pending_boxes"].get<long>() > 0);
  CHECK(j["subproblem_stats"][0]["pending"].size() == j["pending_boxes"].get<size_t>());
  CHECK(j["headline"].get<std::string>().find("search incomplete (interrupted)") != std::string::npos);
  std::stringstream said;
  said << std::ifstream(err).rdbuf();
  CHECK(said.str().find("linkbox: next: to go on from where it stopped: linkbox resume " + cp) != std::string::npos);
}

TEST_CASE("the LP contractor stops between LPs when asked, keeping only proved bounds", "[run_control]") {
  const auto c = formulate::load_case_text(kCircle, "circle.toml");
  const model::System s = c.formulation->subproblem(0).system;
  const model::LphSystem lph = formulate::to_lph(s);
  prune::LpRelaxation lp(lph);
  int asked = 0;
  const std::function<bool()> stop = [&] { return ++asked > 1; };  // the first LP pair only
  lp.stop_when(&stop);
  Box box = lph.domain();
  REQUIRE(lp.contract(box) != prune::Outcome::empty);
  CHECK(lp.lps_solved() <= 2);
  CHECK(asked == 2);
  // Both roots (+-1/sqrt 2, +-1/sqrt 2) are still inside.
  for (double r : {-0.7071067811865476, 0.7071067811865476}) {
    CHECK(boost::numeric::in(r, box[0]));
    CHECK(boost::numeric::in(r, box[1]));
  }
  lp.stop_when(nullptr);
  Box full = lph.domain();
  REQUIRE(lp.contract(full) != prune::Outcome::empty);
  CHECK(lp.lps_solved() > 2);
}

namespace {

// Shrinks every box a little forever, or spoils it with NaN bounds: what a float variant can do.
class Endless final : public prune::Contractor {
 public:
  explicit Endless(bool nan, std::atomic<int>* raise_after = nullptr) : nan_(nan), raise_(raise_after) {}
  std::string name() const override { return "endless"; }
  prune::Outcome contract(Box& box) override {
    if (raise_ && ++calls_ == 1000) raise_->store(1);  // a signal arrives in the middle of one box
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (nan_) {
      box[0] = Interval(nan, nan);
    } else {
      for (auto& x : box) x = Interval(x.lower(), x.upper() - 0.3 * (x.upper() - x.lower()));
    }
    return prune::Outcome::shrunk;
  }
  std::unique_ptr<prune::Contractor> clone() const override { return std::make_unique<Endless>(nan_, raise_); }

 private:
  bool nan_;
  std::atomic<int>* raise_;
  long calls_ = 0;
};

solve::Result search_with(std::unique_ptr<prune::Contractor> c, solve::Params p) {
  std::vector<std::unique_ptr<prune::Contractor>> members;
  members.push_back(std::move(c));
  prune::Sequence seq(std::move(members));
  solve::Budget budget(p);
  solve::Search search(Box{Interval(0, 1), Interval(0, 1)}, seq, {0, 1}, p, budget);
  search.run();
  return search.result();
}

}  // namespace

TEST_CASE("a box whose passes never stop shrinking still yields to an interrupt, and NaN bounds are not a result",
          "[run_control]") {
  std::atomic<int> interrupt{0};
  solve::Params p;
  p.sigma = 1e-300;
  p.rho = 0.99;  // every pass removes more than 1%: one box would take ~1e5 passes
  p.interrupt = &interrupt;
  const solve::Result r = search_with(std::make_unique<Endless>(false, &interrupt), p);
  CHECK_FALSE(r.complete);
  REQUIRE(r.pending.size() == 1);  // the box it was shrinking, back as it was taken
  CHECK(r.pending[0][0].upper() == 1);

  solve::Params q;
  q.sigma = 0.3;
  const solve::Result n = search_with(std::make_unique<Endless>(true), q);
  CHECK(n.complete);
  REQUIRE_FALSE(n.solutions.empty());
  for (auto& b : n.solutions)
    for (auto& x : b) CHECK_FALSE(std::isnan(x.lower()));
  CHECK(n.solutions.size() == 16);  // [0,1]^2 split down to sides 0.25: the boxes as they were
}

TEST_CASE("a budget stops on an interrupt and reads the clock between LPs", "[run_control]") {
  std::atomic<int> interrupt{0};
  solve::Params p;
  p.interrupt = &interrupt;
  solve::Budget budget(p);
  CHECK(budget.take_box());
  CHECK_FALSE(budget.stop_now());
  interrupt = 1;
  CHECK(budget.stop_now());
  CHECK(budget.exhausted());
  CHECK(budget.reason() == "interrupted");
  CHECK_FALSE(budget.take_box());
}

TEST_CASE("a CPU-time limit counts the process's CPU time, not the wall clock", "[run_control]") {
  solve::Params p;
  p.cpu_limit = 0.05;
  solve::Budget budget(p);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // wall time, next to no CPU
  CHECK_FALSE(budget.stop_now());
  volatile double x = 0;
  while (budget.cpu_elapsed() <= p.cpu_limit) x = x + 1;
  CHECK(budget.stop_now());
  CHECK(budget.reason() == "CPU time limit reached");
  CHECK_FALSE(budget.take_box());
}

TEST_CASE("a run stopped by its CPU-time limit is incomplete and says how to go on", "[run_control][cli]") {
  const std::string out = tmp("cpu-limit.json");
  const auto r = run("solve " + src("cases/benchmarks/eco10.toml") + " --cpu-limit 0.3 --json " + out);
  REQUIRE(r.code == 5);
  const auto j = read(out);
  CHECK(j["stop_reason"] == "CPU time limit reached");
  CHECK(j["parameters"]["cpu_limit"] == 0.3);
  CHECK(r.out.find("INCOMPLETE (CPU time limit reached)") != std::string::npos);
  CHECK(r.out.find("linkbox resume " + out) != std::string::npos);  // the run kept a checkpoint beside its JSON
}

TEST_CASE("a race stopped by a limit still says why its lead went where it did", "[run_control][cli]") {
  // No candidate won, so there is no `race` (each one's work, the winner last), but the
  // choices made before the limit are what a user needs to pick a strategy by hand.
  const std::string out = tmp("race-limit.json");
  REQUIRE(run("solve " + src("cases/benchmarks/eco9.toml") + " --quiet --max-boxes 10000 --json " + out).code == 5);
  const auto j = read(out);
  CHECK_FALSE(j.contains("race"));
  REQUIRE(j.contains("race_choices"));
  REQUIRE(j["race_choices"].size() >= 1);
  for (const auto& line : j["race_choices"])
    for (const char* name : {"hc4,newton work", "hc4,newton/lp work", "hc4,newton,taylor work"})
      CHECK(line.get<std::string>().find(name) != std::string::npos);
}

TEST_CASE("a root whose Jacobian is singular is named so, with counts that cannot read as variables", "[run_control][cli]") {
  // x^2 + y^2 = 0 and x^2 = y^3: the one real root is the origin, where every term has degree
  // >= 2, so the Jacobian vanishes there.
  const std::string path = tmp("singular.toml"), out = tmp("singular.json");
  write(path, R"(kind = "polynomial"
name = "singular-origin"
variables = [ { name = "x", domain = [-1, 1] }, { name = "y", domain = [-1, 1] } ]
equations = [ "x^2 + y^2", "x^2 - y^3" ]
)");
  const Ran r = run("solve " + path + " --quiet --json " + out);
  REQUIRE(r.code == 4);  // complete, unresolved
  CHECK(r.out.find("linkbox: next: a singular root") != std::string::npos);
  const auto j = read(out);
  CHECK(j["verification"]["exact"] == false);
  CHECK(j["certified_roots"] == 0);
  const std::string headline = j["headline"];
  INFO(headline);
  CHECK(headline.find("(singular Jacobian in the cluster: 1 cluster)") != std::string::npos);
  CHECK(headline.find(" x1") == std::string::npos);
}

namespace {

// Proves nothing: the search bisects [0, 1]^2 down to sigma, a full binary tree.
class Idle final : public prune::Contractor {
 public:
  std::string name() const override { return "idle"; }
  prune::Outcome contract(Box&) override { return prune::Outcome::unchanged; }
  std::unique_ptr<prune::Contractor> clone() const override { return std::make_unique<Idle>(); }
};

}  // namespace

TEST_CASE("the share of the search tree resolved counts leaves by depth, whatever their volume", "[run_control]") {
  std::vector<std::unique_ptr<prune::Contractor>> members;
  members.push_back(std::make_unique<Idle>());
  prune::Sequence seq(std::move(members));
  solve::Params p;
  p.sigma = 0.3;  // widths 1, 1/2, 1/4: every leaf at depth 4, 16 of them
  solve::Budget budget(p);
  solve::Search search(Box{Interval(0, 1), Interval(0, 1)}, seq, {0, 1}, p, budget);
  CHECK(search.tree_done() == 0);
  double before = 0;
  for (double limit = 1; !search.complete(); limit += 7) {
    search.run(1, limit);
    const double done = search.tree_done();
    CHECK(done >= before);
    CHECK(done == static_cast<double>(search.state().solutions.size()) / 16);
    before = done;
  }
  CHECK(search.tree_done() == 1);
  CHECK(search.result().solutions.size() == 16);
}

TEST_CASE("a limit that stops the refinement after a complete search is said, and resume finishes it",
          "[run_control][cli]") {
  // close-roots' search ends with one box around both roots, 5e-9 apart; the refinement
  // separates them. 40 boxes let the search finish and stop the refinement.
  const std::string out = tmp("refine-limit.json");
  const auto r = run("solve " + src("cases/hard/close-roots.toml") + " --quiet --max-boxes 40 --json " + out);
  REQUIRE(r.code == 5);
  auto j = read(out);
  CHECK(j["complete"] == true);
  CHECK_FALSE(j.contains("stop_reason"));
  REQUIRE(j.contains("refinement_stopped"));
  CHECK(j["refinement_stopped"]["reason"] == "box limit reached");
  CHECK(j["refinement_stopped"]["boxes"].get<long>() >= 1);
  CHECK(j["verification"]["exact"] == false);
  CHECK(j["headline"].get<std::string>().find("refinement stopped (box limit reached)") != std::string::npos);
  CHECK(r.out.find("refinement stopped (box limit reached)") != std::string::npos);
  CHECK(r.out.find("linkbox resume " + out) != std::string::npos);
  CHECK(run("check " + out + " --case " + src("cases/hard/close-roots.toml")).code == 0);

  REQUIRE(run("resume " + out + " --quiet --json " + out).code == 0);
  j = read(out);
  CHECK_FALSE(j.contains("refinement_stopped"));
  CHECK(j["headline"] == "exactly 2 roots in the domain, each in its certified box");
}

TEST_CASE("a complete refinement states no stop", "[run_control][cli]") {
  const std::string out = tmp("refine-whole.json");
  REQUIRE(run("solve " + src("cases/hard/close-roots.toml") + " --quiet --json " + out).code == 0);
  const auto j = read(out);
  CHECK_FALSE(j.contains("refinement_stopped"));
  CHECK(j["headline"] == "exactly 2 roots in the domain, each in its certified box");
}
