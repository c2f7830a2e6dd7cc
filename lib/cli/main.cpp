// The `linkbox` executable: arguments -> options -> load -> solve -> verify -> report.
// Exit codes: 0 success, 1 internal failure or a failed check, 2 bad input (case file or
// arguments), 128 + the signal (130 SIGINT, 143 SIGTERM) when interrupted: what was found is
// still written; under mpirun, 3 when a rank died or an MPI error ended the run.
#include "formulate/load.hpp"
#include "input/to_toml.hpp"
#include "report/json.hpp"
#include "report/text.hpp"
#include "solve/checkpoint.hpp"
#include "solve/output_file.hpp"
#include "solve/solve_case.hpp"
#include "verify/certify_case.hpp"
#include "verify/check.hpp"

#ifdef LINKBOX_MPI
#include "distributed/mpi_solve.hpp"
#include "distributed/mpi_verify.hpp"
#endif

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <unistd.h>

using namespace linkbox;

namespace {

#ifdef LINKBOX_MPI
// Started when mpirun launched this process (distributed/wire.hpp).
std::optional<distributed::World> world;
#endif
bool distributed_run() {
#ifdef LINKBOX_MPI
  return world && world->size() > 1;
#else
  return false;
#endif
}
// Under mpirun only rank 0 prints (the summary, errors); the others work silently.
bool speaks() {
#ifdef LINKBOX_MPI
  return !world || world->rank() == 0;
#else
  return true;
#endif
}

// ---- interrupts: the first stops the search at the next box, the second skips verification.

std::atomic<int> interrupts{0};
volatile std::sig_atomic_t last_signal = 0;

void on_signal(int sig) {
  last_signal = sig;
  static const char first[] =
      "\nlinkbox: interrupted: the search stops at the next box; what was found is verified and written "
      "(interrupt again to skip verification)\n";
  static const char second[] = "\nlinkbox: interrupted again: verification skipped\n";
  const bool again = interrupts.fetch_add(1) > 0;
  // write(2) is async-signal-safe; stdio is not.
  [[maybe_unused]] auto n = again ? write(2, second, sizeof second - 1) : write(2, first, sizeof first - 1);
}

void catch_interrupts() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

// ---- commands

struct SolveCommand {
  std::string case_file, json_out, prune, checkpoint, record_tree;
  solve::RunOptions options;
  bool quiet = false, no_verify = false;
  std::string resume;  // resume: the checkpoint to go on from
  CLI::App* app = nullptr;
  bool given(const char* flag) const { return app->count(flag) > 0; }
};

struct CheckCommand {
  std::string result_file, case_file;
};

// Output problems are bad input, found before the work rather than after it.
void check_writable(const std::string& path, const std::string& flag) {
  if (const std::string why = solve::output_problem(path); !why.empty())
    throw std::invalid_argument(flag + " " + path + ": " + why);
}

// FNV-1a of the case file's bytes: a checkpoint is for this exact text.
std::string file_hash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::uint64_t h = 1469598103934665603ull;
  for (char c; in.get(c);) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  char out[17];
  std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h));
  return out;
}

// The settings that decide the boxes, as a checkpoint records them.
nlohmann::json search_settings(const solve::RunOptions& o) {
  return {{"sigma", o.params.sigma},
          {"rho", o.params.rho},
          {"order", o.params.order == solve::Order::depth_first ? "dfs" : "bfs"},
          {"prune", o.strategy.prune.text()},
          {"bisect", solve::to_string(o.bisect)},
          {"lp", prune::lp::to_string(o.strategy.lp)},
          {"arith", to_string(o.strategy.arith)}};
}

// Flags, then the case's [solve] table, then the defaults.
void resolve_settings(SolveCommand& cmd, const input::SolveSettings& s, const std::string& file) {
  solve::RunOptions& o = cmd.options;
  auto from_case = [&](const char* flag, const char* name, const auto& value, auto apply) {
    if (cmd.given(flag)) {
      o.setting_source[name] = "flag";
    } else if (value) {
      try {
        apply(*value);
      } catch (const std::invalid_argument& e) {
        throw input::InputError(file, s.line, std::string("[solve] ") + name + ": " + e.what());
      }
      o.setting_source[name] = "case file";
    }
  };
  from_case("--sigma", "sigma", s.sigma, [&](double x) { o.params.sigma = x; });
  from_case("--rho", "rho", s.rho, [&](double x) { o.params.rho = x; });
  from_case("--time-limit", "time_limit", s.time_limit, [&](double x) { o.params.time_limit = x; });
  o.strategy.prune = solve::Strategy::parse(cmd.prune);
  from_case("--prune", "prune", s.prune, [&](const std::string& x) { o.strategy.prune = solve::Strategy::parse(x); });
  from_case("--bisect", "bisect", s.bisect, [&](const std::string& x) { o.bisect = solve::parse_bisect(x); });
}

// A resumed run takes the checkpoint's settings; a flag that says otherwise is refused.
void resume_settings(SolveCommand& cmd, const nlohmann::json& saved) {
  solve::RunOptions& o = cmd.options;
  o.strategy.prune = solve::Strategy::parse(cmd.prune);
  const nlohmann::json asked = search_settings(o);
  auto take = [&](const char* flag, const char* name, auto apply) {
    if (cmd.given(flag) && asked.at(name) != saved.at(name))
      throw std::invalid_argument("the checkpoint was made with " + std::string(name) + " " + saved.at(name).dump() +
                                  ", not " + asked.at(name).dump() + ": resume it with the same settings, or start afresh");
    apply(saved.at(name));
  };
  take("--sigma", "sigma", [&](const nlohmann::json& v) { o.params.sigma = v; });
  take("--rho", "rho", [&](const nlohmann::json& v) { o.params.rho = v; });
  take("--order", "order", [&](const nlohmann::json& v) {
    o.params.order = v == "bfs" ? solve::Order::breadth_first : solve::Order::depth_first;
  });
  take("--prune", "prune", [&](const nlohmann::json& v) { o.strategy.prune = solve::Strategy::parse(v.get<std::string>()); });
  take("--bisect", "bisect", [&](const nlohmann::json& v) { o.bisect = solve::parse_bisect(v); });
  take("--lp", "lp", [&](const nlohmann::json& v) {
    o.strategy.lp = v == "exact" ? prune::lp::LpBackend::exact : prune::lp::LpBackend::safe;
  });
  take("--arith", "arith", [&](const nlohmann::json& v) {
    o.strategy.arith = v == "verified" ? Arith::verified : Arith::float_unverified;
  });
  for (auto& [name, value] : saved.items()) o.setting_source[name] = "checkpoint";
  if (search_settings(o) != saved)
    throw std::invalid_argument("the checkpoint's settings " + saved.dump() + " are not understood by this linkbox");
}

verify::VerifyOptions verify_options(const SolveCommand& cmd) {
  verify::VerifyOptions vo;
  vo.skip_rest = [] { return interrupts.load() >= 2; };
  vo.threads = cmd.options.threads;
  vo.progress = !cmd.quiet;
  return vo;
}

// Runs verification: `verifying` false (a second interrupt) skips it, and returns nothing.
using Verifier = std::function<std::optional<verify::VerifyReport>(bool verifying, const verify::VerifyOptions&)>;

// A search's result to the summary and the JSON, then verification (unless --no-verify).
// `extra` goes into the JSON, asked each time it is written.
int report_and_verify(const SolveCommand& cmd, const formulate::LoadedCase& c, const solve::CaseResult& r,
                      const std::function<nlohmann::json()>& extra, const Verifier& verifier) {
  const solve::RunOptions& o = cmd.options;
  // `--json -` puts the JSON on standard output, alone: the summary goes to stderr.
  std::FILE* text = cmd.json_out == "-" ? stderr : stdout;
  report::print_summary(text, c, o, r);
  std::fflush(text);  // before verification's progress lines on stderr
  nlohmann::json j = report::result_json(c.name, c.file, *c.formulation, o, r);
  j.update(extra());
  // mpirun answers an interrupt with SIGTERM to every rank and SIGKILL a second later: the
  // search's result is on disk before verification starts, and replaced once it is verified.
  if (distributed_run() && interrupts.load() && !cmd.json_out.empty() && cmd.json_out != "-")
    solve::write_output(cmd.json_out, j.dump(1) + '\n');
  if (!cmd.no_verify) {
    if (const auto v = verifier(interrupts.load() < 2, verify_options(cmd))) {
      report::print_verification(text, c, *v);
      report::add_verification(j, *c.formulation, *v);
      j.update(extra());
    }
  }
  if (!cmd.json_out.empty()) solve::write_output(cmd.json_out, j.dump(1) + '\n');
  std::fflush(text);
  return interrupts.load() ? 128 + last_signal : 0;
}

int run_solve(SolveCommand& cmd) {
  solve::RunOptions& o = cmd.options;
  o.progress = !cmd.quiet;
  o.params.interrupt = &interrupts;
  if (distributed_run() && (!cmd.checkpoint.empty() || !cmd.resume.empty() || !cmd.record_tree.empty()))
    throw std::invalid_argument("checkpoints (--checkpoint, resume) and --record-tree are for runs of one process, not under mpirun");
  if (speaks()) {
    check_writable(cmd.json_out, "--json");
    if (cmd.checkpoint == "-")
      throw std::invalid_argument("--checkpoint -: a checkpoint is rewritten during the run, so it needs a file");
    check_writable(cmd.checkpoint, "--checkpoint");
    check_writable(cmd.record_tree, "--record-tree");
  }

  std::optional<solve::Checkpoint> saved;
  nlohmann::json header;
  if (!cmd.resume.empty()) {
    saved = solve::read_checkpoint(cmd.resume);
    header = nlohmann::json::parse(saved->header);
    if (cmd.case_file.empty()) cmd.case_file = header.value("case_file", "");
  }
  const formulate::LoadedCase c = formulate::load_case(cmd.case_file);
  const std::string hash = file_hash(cmd.case_file);
  if (saved) {
    if (header.value("case_hash", "") != hash)
      throw std::invalid_argument("checkpoint " + cmd.resume + " was made for another case (" +
                                  header.value("case_file", "?") + ", " + header.value("case_name", "?") +
                                  ") or that file has changed since: " + cmd.case_file + " does not match it");
    resume_settings(cmd, header.at("settings"));
    if (!cmd.given("--time-limit") && c.solve.time_limit) o.params.time_limit = *c.solve.time_limit;
    o.resume = &*saved;
  } else {
    resolve_settings(cmd, c.solve, c.file);
  }
  if (!cmd.checkpoint.empty()) {
    o.checkpoint = cmd.checkpoint;
    o.checkpoint_header =
        nlohmann::json{{"case_file", c.file}, {"case_name", c.name}, {"case_hash", hash}, {"settings", search_settings(o)}}
            .dump();
  }
  if (interrupts.load()) return 128 + last_signal;  // before any work: nothing to keep

#ifdef LINKBOX_MPI
  if (distributed_run()) {
    distributed::Figures figures;
    const auto r = distributed::solve_distributed(*c.formulation, o, *world, &figures);
    if (!r) {  // a worker: rank 0 reports
      if (!cmd.no_verify) distributed::verify_distributed(*c.formulation, nullptr, verify_options(cmd), *world, nullptr);
      return interrupts.load() ? 128 + last_signal : 0;
    }
    return report_and_verify(
        cmd, c, *r, [&] { return nlohmann::json{{"distributed", figures.json()}}; },
        [&](bool verifying, const verify::VerifyOptions& vo) {
          return distributed::verify_distributed(*c.formulation, verifying ? &*r : nullptr, vo, *world, &figures);
        });
  }
#endif
  solve::BoxLog log;
  if (!cmd.record_tree.empty()) o.box_log = &log;
  const solve::CaseResult r = solve::solve_case(*c.formulation, o);
  if (!cmd.record_tree.empty()) {
    std::string csv = "subproblem,candidate,path,outcome,seconds\n";
    for (auto& e : log.take()) {
      char seconds[32];
      std::snprintf(seconds, sizeof seconds, "%.4g", e.seconds);
      csv += std::to_string(e.subproblem) + ',' + std::to_string(e.candidate) + ',' + e.path + ',' + e.outcome + ',' +
             seconds + '\n';
    }
    solve::write_output(cmd.record_tree, csv);
  }
  return report_and_verify(
      cmd, c, r, [] { return nlohmann::json::object(); },
      [&](bool verifying, const verify::VerifyOptions& vo) {
        return verifying ? std::optional(verify::verify_case(*c.formulation, r, vo)) : std::nullopt;
      });
}

int run_check(const CheckCommand& cmd) {
  std::ifstream in(cmd.result_file);
  if (!in) throw std::invalid_argument("cannot read " + cmd.result_file);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(cmd.result_file + ": not a linkbox result: " + e.what());
  }
  if (!j.contains("clusters"))
    throw std::invalid_argument(cmd.result_file + ": no certificates (was it run with --no-verify?)");
  const formulate::LoadedCase c =
      formulate::load_case(cmd.case_file.empty() ? j.at("case_file").get<std::string>() : cmd.case_file);
  verify::CheckOutcome out;
  try {
    out = verify::check_certificates(j, *c.formulation);
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(cmd.result_file + ": malformed certificate data: " + e.what());
  }
  for (auto& f : out.failures) std::fprintf(stderr, "FAILED: %s\n", f.c_str());
  if (!out.failures.empty()) {
    std::fprintf(stderr, "%zu of the certificates in %s do not hold\n", out.failures.size(), cmd.result_file.c_str());
    return 1;
  }
  std::printf("%d certificates re-checked from %s and %s: all hold (%s)\n", out.checked, cmd.result_file.c_str(),
              c.file.c_str(), j.value("headline", "").c_str());
  return 0;
}

// ---- options

// CLI11's own range messages print the whole of DBL_MAX; these say what is expected.
CLI::Validator number(double lo, bool lo_open, double hi = INFINITY) {
  std::string want = std::string("a number ") + (lo_open ? "> " : ">= ") + CLI::detail::to_string(lo);
  if (hi < INFINITY) want += " and <= " + CLI::detail::to_string(hi);
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        char* end = nullptr;
        const double x = std::strtod(text.c_str(), &end);
        const bool ok = end != text.c_str() && *end == '\0' && (lo_open ? x > lo : x >= lo) && x <= hi;
        return ok ? "" : "expected " + want + ", got '" + text + "'";
      },
      want.substr(2), "");
}

void add_search_options(CLI::App& cmd, SolveCommand& s) {
  solve::RunOptions& o = s.options;
  cmd.add_option("--sigma", o.params.sigma, "solution box size (default 1e-4, or the case's [solve] table)")
      ->check(number(0, true));
  cmd.add_option("--rho", o.params.rho, "split when volume ratio after a shrink exceeds rho (default: 0.99 on spherical cases, the papers' value; 0.8 elsewhere)")->check(number(0, true, 1));
  cmd.add_option("--order", o.params.order, "dfs or bfs")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, solve::Order>{{"dfs", solve::Order::depth_first}, {"bfs", solve::Order::breadth_first}}));
  s.prune = o.strategy.prune.text();  // the default
  cmd.add_option("--prune", s.prune,
                 "contractors: auto (default), or a comma-separated list of " + solve::contractor_names() +
                     "; '/' starts a stage that runs only when the earlier ones stall, e.g. hc4,newton/lp");
  cmd.add_option("--bisect", o.bisect, "auto (default), widest, round-robin or smear")
      ->transform(CLI::CheckedTransformer(std::map<std::string, solve::Bisect>{{"auto", solve::Bisect::automatic},
                                                                              {"widest", solve::Bisect::widest},
                                                                              {"round-robin", solve::Bisect::round_robin},
                                                                              {"smear", solve::Bisect::smear}}));
  cmd.add_option("--lp", o.strategy.lp, "LP backend: safe or exact")
      ->transform(CLI::CheckedTransformer(std::map<std::string, prune::lp::LpBackend>{
          {"safe", prune::lp::LpBackend::safe}, {"exact", prune::lp::LpBackend::exact}}));
  cmd.add_option("--arith", o.strategy.arith, "verified (default) or float: the UNVERIFIED float variant, for comparison")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, Arith>{{"verified", Arith::verified}, {"float", Arith::float_unverified}}));
}

void add_run_options(CLI::App& cmd, SolveCommand& s) {
  solve::RunOptions& o = s.options;
  cmd.add_option("--time-limit", o.params.time_limit, "seconds (0 = none); the search stops and keeps what it proved")
      ->check(number(0, false));
  cmd.add_option("--max-boxes", o.params.max_boxes, "processed boxes (0 = none)")->check(number(0, false));
  cmd.add_option("--threads", o.threads, "threads: sub-problems in parallel, and the boxes of each search")->check(CLI::Range(1, 256));
  cmd.add_option("--json", s.json_out, "write the result as JSON ('-': standard output, the summary then on stderr)");
  cmd.add_option("--checkpoint", s.checkpoint, "save the run's state to this file, to go on with `linkbox resume`");
  cmd.add_option("--checkpoint-every", o.checkpoint_every, "seconds between checkpoints (default 60)")
      ->check(number(0, true));
  cmd.add_flag("--quiet", s.quiet, "no progress on stderr");
  cmd.add_option("--record-tree", s.record_tree,
                 "write every processed box (sub-problem, raced candidate, path, outcome, seconds) as CSV: the "
                 "search tree that papers/benchmarks/scaling.py replays");
  cmd.add_flag("--no-verify", s.no_verify, "skip clustering and certification");
}

// CLP's LAPACK may be OpenBLAS, whose thread pool starts at load time and busy-waits for
// work for a while: about 0.15 s of CPU per run, which is most of a small case. linkbox makes
// no BLAS calls worth threading; the setting is read at load, so set it and start again once.
void single_threaded_blas(char** argv) {
  if (std::getenv("OPENBLAS_NUM_THREADS")) return;
  setenv("OPENBLAS_NUM_THREADS", "1", 1);
  execv("/proc/self/exe", argv);  // returns only on failure: then run as we are
}

}  // namespace

int main(int argc, char** argv) {
  single_threaded_blas(argv);
#ifdef LINKBOX_MPI
  if (distributed::World::launched()) world.emplace(&argc, &argv);
#endif
  CLI::App app{"linkbox: verified position analysis of linkages by interval branch-and-prune"};
  app.set_version_flag("--version", "linkbox " LINKBOX_VERSION);
  app.require_subcommand(1);
  SolveCommand solve_cmd;
  auto* solve_app = app.add_subcommand("solve", "enclose every root of a case in solution boxes");
  solve_app->add_option("case", solve_cmd.case_file, "case file (TOML; or a peer's .bch or .cuik)")->required();
  add_search_options(*solve_app, solve_cmd);
  add_run_options(*solve_app, solve_cmd);
  solve_cmd.app = solve_app;
  SolveCommand resume_cmd;
  auto* resume_app = app.add_subcommand(
      "resume", "go on with a run saved by --checkpoint; it ends with the boxes an unbroken run gives");
  resume_app->add_option("checkpoint", resume_cmd.resume, "the checkpoint file")->required();
  resume_app->add_option("--case", resume_cmd.case_file, "case file (default: the one named in the checkpoint)");
  add_search_options(*resume_app, resume_cmd);
  add_run_options(*resume_app, resume_cmd);
  resume_cmd.app = resume_app;
  CheckCommand check_cmd;
  auto* check_app = app.add_subcommand("check", "re-check every certificate of a result JSON (no search)");
  check_app->add_option("result", check_cmd.result_file, "JSON written by solve --json")->required();
  check_app->add_option("--case", check_cmd.case_file, "case file (default: the one named in the JSON)");
  std::string convert_file;
  auto* convert_app = app.add_subcommand("convert", "write a peer's model (Minibex .bch, CuikSuite .cuik) as a TOML case");
  convert_app->add_option("model", convert_file, "the .bch or .cuik file")->required();
  solve_app->footer(R"(Examples:
  linkbox solve cases/linkages/6r-rigid.toml
  linkbox solve cases/linkages/cyclohexane.toml --prune lp --json out.json
  linkbox solve cases/benchmarks/eco9.bch --time-limit 60 --checkpoint eco9.ckpt
  linkbox solve case.toml --arith float        (unverified, for comparison)
Settings come from the flags, else the case's [solve] table, else the defaults; the summary's
`settings` line says which. Exit 0 (also when a limit stopped the search: the JSON says
complete: false), 2 bad input, 1 internal error, 128+N on signal N.)");
  resume_app->footer(R"(Examples:
  linkbox resume eco9.ckpt
  linkbox resume eco9.ckpt --time-limit 600 --json eco9.json
A checkpoint of another case, or with other search settings, is refused (exit 2).)");
  check_app->footer(R"(Examples:
  linkbox solve cases/spherical/wrist.toml --json wrist.json && linkbox check wrist.json
  linkbox check result.json --case my-copy-of-the-case.toml)");
  convert_app->footer(R"(Examples:
  linkbox convert cases/benchmarks/eco9.bch > eco9.toml
  linkbox convert cases/benchmarks/cyclohexan3d.cuik > cyclohexan3d.toml
An unsupported construct is an error naming file:line (exit 2), never a change of meaning.)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::ostringstream silent;
    int code = speaks() ? app.exit(e) : app.exit(e, silent, silent);
    return code == 0 ? 0 : 2;
  }
  try {
    if (*solve_app || *resume_app) catch_interrupts();
    if (*solve_app) return run_solve(solve_cmd);
    if (*resume_app) return run_solve(resume_cmd);
    if (*check_app) return run_check(check_cmd);
    if (*convert_app) {
      std::fputs(input::convert_to_toml(convert_file).c_str(), stdout);
      return 0;
    }
  } catch (const input::InputError& e) {
    if (speaks()) std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::invalid_argument& e) {
    if (speaks()) std::fprintf(stderr, "linkbox: %s\n", e.what());
    return 2;
#ifdef LINKBOX_MPI
  } catch (const distributed::Failed& e) {  // from another rank's search, worded as the CLI words it
    std::fprintf(stderr, "%s\n", e.what());
    return e.code;
  } catch (const distributed::Ended& e) {
    return e.code;
#endif
  } catch (const std::exception& e) {
#ifdef LINKBOX_MPI
    // An error of this rank alone: the others would wait for it until their timeout.
    if (distributed_run()) world->fail(std::string("internal error: ") + e.what(), 1);
#endif
    if (speaks()) std::fprintf(stderr, "linkbox: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
