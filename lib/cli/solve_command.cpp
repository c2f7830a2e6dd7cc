#include "cli/solve_command.hpp"

#include "cli/interrupts.hpp"
#include "cli/run_mode.hpp"
#include "cli/settings.hpp"
#include "formulate/load.hpp"
#include "solve/checkpoint.hpp"
#include "solve/output_file.hpp"
#include "verify/symmetric_map.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>

namespace linkbox::cli {

bool SolveCommand::given(const char* flag) const { return app->count(flag) > 0; }

namespace {

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
      "", "");  // no description: the help shows the option's plain type name
}

// A choice among words, shown in the help as `type`, e.g. "dfs|bfs".
template <class T>
CLI::Validator choice(const std::map<std::string, T>& words) {
  return CLI::CheckedTransformer(words).description("");
}

void add_search_flags(CLI::App& cmd, SolveCommand& s) {
  solve::RunOptions& o = s.options;
  cmd.add_option("--sigma", o.params.sigma, "solution box size (default 1e-4, or the case's [solve] table)")
      ->check(number(0, true))
      ->type_name("S");
  cmd.add_option("--rho", o.params.rho, "split when volume ratio after a shrink exceeds rho, 0 < R <= 1 (default: 0.99 on spherical cases, the papers' value; 0.8 elsewhere)")
      ->check(number(0, true, 1))
      ->type_name("R");
  cmd.add_option("--narrow", o.params.narrow, "after the search, narrow uncertified solution boxes to width W (by hc4,newton,taylor, whatever --prune), for curve maps that need narrow boxes (default: 0.02 on a symmetric six-joint loop, whose curve map needs it; 0 elsewhere)")
      ->check(number(0, false))
      ->type_name("W");
  cmd.add_option("--order", o.params.order, "depth- or breadth-first order of the boxes (default dfs)")
      ->transform(choice(
          std::map<std::string, solve::Order>{{"dfs", solve::Order::depth_first}, {"bfs", solve::Order::breadth_first}}))
      ->type_name("dfs|bfs");
  s.prune = o.strategy.prune.text();  // the default
  cmd.add_option("--prune", s.prune,
                 "contractors: auto (default), or a comma-separated list of " + solve::contractor_names() +
                     "; '/' starts a stage that runs only when the earlier ones stall, e.g. hc4,newton/lp")
      ->type_name("LIST");
  cmd.add_option("--bisect", o.bisect, "the variable to split (default auto)")
      ->type_name("auto|widest|round-robin|smear")
      ->transform(choice(std::map<std::string, solve::Bisect>{{"auto", solve::Bisect::automatic},
                                                                              {"widest", solve::Bisect::widest},
                                                                              {"round-robin", solve::Bisect::round_robin},
                                                                              {"smear", solve::Bisect::smear}}));
  cmd.add_option("--lp", o.strategy.lp, "the LP backend of the lp contractor (default safe)")
      ->type_name("safe|exact")
      ->transform(choice(std::map<std::string, prune::lp::LpBackend>{
          {"safe", prune::lp::LpBackend::safe}, {"exact", prune::lp::LpBackend::exact}}));
  cmd.add_option("--lp-order", o.strategy.lp_order,
                 "which bound the lp contractor tightens next: the open bound nearest the last LP's optimum "
                 "(default), or each variable's lower then upper bound in turn, as the iterated-LP paper's Algorithm 2")
      ->type_name("nearest|given")
      ->transform(choice(std::map<std::string, prune::lp::Order>{{"nearest", prune::lp::Order::nearest_bound},
                                                                 {"given", prune::lp::Order::given}}));
  cmd.add_option("--arith", o.strategy.arith, "float is the UNVERIFIED float variant, for comparison (default verified)")
      ->type_name("verified|float")
      ->transform(choice(
          std::map<std::string, Arith>{{"verified", Arith::verified}, {"float", Arith::float_unverified}}));
}

void add_run_flags(CLI::App& cmd, SolveCommand& s) {
  solve::RunOptions& o = s.options;
  cmd.add_option("--time-limit", o.params.time_limit, "stop the search after SEC seconds, keeping what it proved; verification gets as long again "
                 "(default 0: none)")
      ->check(number(0, false))
      ->type_name("SEC");
  cmd.add_option("--cpu-limit", o.params.cpu_limit,
                 "stop the search after SEC seconds of the process's CPU time (all threads), keeping what it "
                 "proved: a limit that a loaded machine does not shorten; verification gets as long again, in wall "
                 "seconds (default 0: none)")
      ->check(number(0, false))
      ->type_name("SEC");
  cmd.add_option("--max-boxes", o.params.max_boxes, "stop the search after N processed boxes (default 0: none)")
      ->check(number(0, false))
      ->type_name("N");
  cmd.add_option("--threads", o.threads, "1 to 256 threads: sub-problems in parallel, and the boxes of each search (default 1)")
      ->check(CLI::Range(1, 256).description(""))
      ->type_name("T");
  cmd.add_option("--json", s.json_out, "write the result as JSON ('-': standard output, the summary then on stderr) (default: none)")
      ->type_name("OUT");
  cmd.add_option("--checkpoint", s.checkpoint, "save the run's state to this file, to go on with `linkbox resume` (default: none)")
      ->type_name("FILE");
  cmd.add_option("--checkpoint-every", o.checkpoint_every, "seconds between checkpoints (default 60)")
      ->check(number(0, true))
      ->type_name("SEC");
  cmd.add_flag("--quiet", s.quiet, "no progress on stderr");
  cmd.add_option("--record-tree", s.record_tree,
                 "write every processed box (sub-problem, raced candidate, path, outcome, seconds) as CSV: the "
                 "search tree that papers/benchmarks/scaling.py replays (default: none)")
      ->type_name("FILE");
  cmd.add_flag("--no-verify", s.no_verify, "skip clustering and certification");
}

// Output problems are bad input, found before the work rather than after it.
void check_writable(const std::string& path, const std::string& flag) {
  if (const std::string why = solve::output_problem(path); !why.empty())
    throw std::invalid_argument(flag + " " + path + ": " + why);
}

void check_outputs(const SolveCommand& cmd, const RunMode& mode) {
  if (mode.distributed() && (!cmd.checkpoint.empty() || !cmd.resume.empty() || !cmd.record_tree.empty()))
    throw std::invalid_argument("checkpoints (--checkpoint, resume) and --record-tree are for runs of one process, not under mpirun");
  if (!mode.speaks()) return;
  check_writable(cmd.json_out, "--json");
  if (cmd.checkpoint == "-")
    throw std::invalid_argument("--checkpoint -: a checkpoint is rewritten during the run, so it needs a file");
  check_writable(cmd.checkpoint, "--checkpoint");
  check_writable(cmd.record_tree, "--record-tree");
}

// The checkpoint kept beside `--json OUT` (none under mpirun, with --checkpoint, for stdout,
// or where it could not be written).
std::string kept_checkpoint(const SolveCommand& cmd, const RunMode& mode) {
  if (mode.distributed() || !cmd.checkpoint.empty() || cmd.json_out.empty() || cmd.json_out == "-") return {};
  const std::string path = cmd.json_out + ".ckpt";
  return solve::output_problem(path).empty() ? path : std::string();
}

// `linkbox resume OUT.json`: the checkpoint an incomplete result names, found as written or
// beside the result; any other file is read as a checkpoint.
std::string checkpoint_of(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("format") || !j.contains("checkpoint")) return file;
  return found_beside(j.at("checkpoint").get<std::string>(), file);
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

// The checkpoint to resume from, when resuming, with its header.
struct SavedRun {
  std::optional<solve::Checkpoint> saved;
  nlohmann::json header;
};

void check_same_case(const SolveCommand& cmd, const nlohmann::json& header, const std::string& hash) {
  if (header.value("case_hash", "") != hash)
    throw std::invalid_argument("checkpoint " + cmd.resume + " was made for another case (" +
                                header.value("case_file", "?") + ", " + header.value("case_name", "?") +
                                ") or that file has changed since: " + cmd.case_file + " does not match it");
}

// The run's options from the flags, the case and the checkpoint (when resuming).
void settle_options(SolveCommand& cmd, const formulate::LoadedCase& c, SavedRun& resumed, const std::string& hash) {
  solve::RunOptions& o = cmd.options;
  if (resumed.saved) check_same_case(cmd, resumed.header, hash);
  o.strategy.prune = solve::Strategy::parse(cmd.prune);
  if (resumed.saved) {
    resume_settings(cmd, resumed.header.at("settings"));
    if (!cmd.given("--time-limit") && c.solve.time_limit) o.params.time_limit = *c.solve.time_limit;
    o.resume = &*resumed.saved;
  } else {
    resolve_settings(cmd, c.solve, c.file);
  }
  // A symmetric six-joint loop's curve map needs narrow members (verify/symmetric_map.hpp).
  if (cmd.given("--narrow")) {
    o.setting_source["narrow"] = "flag";
  } else if (!cmd.no_verify && verify::SymmetricLoop::of(*c.formulation)) {
    o.params.narrow = verify::kSymmetricPiece;
    o.setting_source["narrow"] = "symmetric loop";
  }
  const std::string& checkpoint = cmd.checkpoint.empty() ? cmd.kept_checkpoint : cmd.checkpoint;
  if (!checkpoint.empty()) {
    o.checkpoint = checkpoint;
    o.checkpoint_header =
        nlohmann::json{{"case_file", c.file}, {"case_name", c.name}, {"case_hash", hash}, {"settings", search_settings(o)}}
            .dump();
  }
}

}  // namespace

std::string found_beside(const std::string& named, const std::string& result_file) {
  namespace fs = std::filesystem;
  if (fs::exists(named) || fs::path(named).is_absolute()) return named;
  const fs::path folder = fs::path(result_file).parent_path();
  for (const fs::path& p : {folder / named, folder / fs::path(named).filename()})
    if (fs::exists(p)) return p.string();
  return named;
}

void add_solve_flags(CLI::App& app, SolveCommand& s) {
  add_search_flags(app, s);
  add_run_flags(app, s);
  s.app = &app;
}

int run_solve(SolveCommand& cmd, const RunMode& mode) {
  cmd.options.progress = !cmd.quiet;
  cmd.options.params.interrupt = &interrupts();
  check_outputs(cmd, mode);
  cmd.kept_checkpoint = kept_checkpoint(cmd, mode);
  SavedRun resumed;
  if (!cmd.resume.empty()) {
    cmd.resume = checkpoint_of(cmd.resume);
    resumed.saved = solve::read_checkpoint(cmd.resume);
    resumed.header = nlohmann::json::parse(resumed.saved->header);
    if (cmd.case_file.empty()) cmd.case_file = resumed.header.value("case_file", "");
  }
  const formulate::LoadedCase c = formulate::load_case(cmd.case_file);
  settle_options(cmd, c, resumed, file_hash(cmd.case_file));
  if (interrupts().load()) return interrupt_exit_code();  // before any work: nothing to keep
  return mode.solve(cmd, c);
}

verify::VerifyOptions verify_options(const SolveCommand& cmd) {
  verify::VerifyOptions vo;
  vo.skip_rest = [] { return interrupts().load() >= 2; };
  vo.time_limit = std::max(cmd.options.params.time_limit, cmd.options.params.cpu_limit);
  vo.threads = cmd.options.threads;
  vo.progress = !cmd.quiet;
  return vo;
}

}  // namespace linkbox::cli
