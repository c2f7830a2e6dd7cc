// The `linkbox` executable: arguments -> options -> load -> solve -> verify -> report.
// Exit codes: 0 success, 1 internal failure or a failed check, 2 bad input (case file or
// arguments).
#include "formulate/load.hpp"
#include "report/json.hpp"
#include "report/text.hpp"
#include "solve/solve_case.hpp"
#include "verify/certify_case.hpp"
#include "verify/check.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <unistd.h>
#include <fstream>
#include <map>

using namespace linkbox;

namespace {

struct SolveCommand {
  std::string case_file, json_out, prune;
  solve::RunOptions options;
  bool quiet = false, no_verify = false;
};

struct CheckCommand {
  std::string result_file, case_file;
};

void write_json(const std::string& path, const nlohmann::json& j) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << j.dump(1) << '\n';
}

int run_solve(SolveCommand& cmd) {
  solve::RunOptions& o = cmd.options;
  o.strategy.contractors = solve::parse_strategy_list(cmd.prune);
  o.progress = !cmd.quiet;

  const formulate::LoadedCase c = formulate::load_case(cmd.case_file);
  const solve::CaseResult r = solve::solve_case(*c.formulation, o);
  report::print_summary(stdout, c, o, r);
  nlohmann::json j = report::result_json(c.name, c.file, *c.formulation, o, r);
  if (!cmd.no_verify) {
    const verify::VerifyReport v = verify::verify_case(*c.formulation, r);
    report::print_verification(stdout, c, v);
    report::add_verification(j, *c.formulation, v);
  }
  if (!cmd.json_out.empty()) write_json(cmd.json_out, j);
  return 0;
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

void add_solve_options(CLI::App& cmd, SolveCommand& s) {
  solve::RunOptions& o = s.options;
  cmd.add_option("case", s.case_file, "case file (TOML)")->required();
  cmd.add_option("--sigma", o.params.sigma, "solution box size")->check(CLI::PositiveNumber);
  cmd.add_option("--rho", o.params.rho, "split when volume ratio after a shrink exceeds rho")
      ->check(CLI::Range(0.0, 1.0));
  cmd.add_option("--order", o.params.order, "dfs or bfs")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, solve::Order>{{"dfs", solve::Order::depth_first}, {"bfs", solve::Order::breadth_first}}));
  s.prune = solve::strategy_name(o.strategy.contractors);  // the default
  cmd.add_option("--prune", s.prune,
                 "contractors: auto (default), or a comma-separated list of trapezoid, hc4, newton, lp; '/' starts a "
                 "stage that runs only when the earlier ones stall, e.g. hc4,newton/lp");
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
  cmd.add_option("--time-limit", o.params.time_limit, "seconds (0 = none)")->check(CLI::NonNegativeNumber);
  cmd.add_option("--max-boxes", o.params.max_boxes, "processed boxes (0 = none)")->check(CLI::NonNegativeNumber);
  cmd.add_option("--threads", o.threads, "threads across sub-problems")->check(CLI::Range(1, 256));
  cmd.add_option("--json", s.json_out, "write the result as JSON");
  cmd.add_flag("--quiet", s.quiet, "no progress on stderr");
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
  CLI::App app{"linkbox: verified position analysis of linkages by interval branch-and-prune"};
  app.require_subcommand(1);
  SolveCommand solve_cmd;
  auto* solve_app = app.add_subcommand("solve", "enclose every root of a case in solution boxes");
  add_solve_options(*solve_app, solve_cmd);
  CheckCommand check_cmd;
  auto* check_app = app.add_subcommand("check", "re-check every certificate of a result JSON (no search)");
  check_app->add_option("result", check_cmd.result_file, "JSON written by solve --json")->required();
  check_app->add_option("--case", check_cmd.case_file, "case file (default: the one named in the JSON)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  try {
    if (*solve_app) return run_solve(solve_cmd);
    if (*check_app) return run_check(check_cmd);
  } catch (const input::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "linkbox: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "linkbox: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
