// The `linkbox` executable: parses arguments and calls the library. Exit codes: 0 success,
// 1 internal failure, 2 bad input (case file or arguments).
#include "io/case_file.hpp"
#include "io/result_json.hpp"
#include "io/verify_json.hpp"
#include "verify/certify_case.hpp"
#include "solve/solve_case.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <iostream>

using namespace linkbox;

namespace {

struct SolveArgs {
  std::string case_file;
  double sigma = 1e-4, rho = 0.99;
  std::string order = "dfs", prune = "trapezoid", lp = "safe", arith = "verified", json_out;
  double time_limit = 0;
  long max_boxes = 0;
  int threads = 1;
  bool quiet = false;
  bool no_verify = false;
};

struct CheckArgs {
  std::string result_file, case_file;
};

void print_roots(const io::LoadedCase& c, const verify::VerifyReport& v) {
  const auto names = c.formulation->output_names();
  std::printf("\nverification (%.3f s): %s\n", v.seconds, v.headline.c_str());
  int k = 0;
  for (auto& cl : v.clusters) {
    if (cl.status != verify::ClusterStatus::certified || cl.duplicate_of >= 0) continue;
    std::printf("  root %2d:", ++k);
    for (size_t i = 0; i < cl.root.size(); ++i) std::printf(" %s=%+.12f", names[i].c_str(), median(cl.root[i]));
    std::printf("  (certified box width %.1e)\n", max_width(cl.root));
  }
  for (auto& cl : v.clusters) {
    if (cl.status == verify::ClusterStatus::curve)
      std::printf("  curve: %zu boxes, %d/%zu crossings certified\n", cl.boxes.size(), cl.crossings_certified,
                  cl.crossings.size());
    else if (cl.status == verify::ClusterStatus::unverified)
      std::printf("  unverified cluster of %zu boxes: %s\n", cl.boxes.size(), cl.reason.c_str());
  }
}

void print_summary(const io::LoadedCase& c, const solve::RunOptions& o, const solve::CaseResult& r) {
  const auto& f = *c.formulation;
  std::printf("case      %s (%s, %s)\n", c.name.c_str(), c.kind.c_str(), c.file.c_str());
  std::string prune;
  for (auto& n : r.contractor_names) prune += (prune.empty() ? "" : ",") + n;
  std::printf("strategy  prune=%s sigma=%g rho=%g order=%s threads=%d%s\n", prune.c_str(), o.params.sigma,
              o.params.rho, o.params.order == solve::Order::depth_first ? "dfs" : "bfs", o.threads,
              o.strategy.rigorous ? "" : "  arith=float (UNVERIFIED: boxes discarded on float evidence)");
  if (f.subproblem_count() == 1)
    if (auto sub = f.subproblem(0); sub.lph)
      std::printf("model     %zu primary + %zu dummy variables; %zu linear, %zu parabolic, %zu hyperbolic equations\n",
                  sub.lph->primary.size(), sub.lph->variables.size() - sub.lph->primary.size(), sub.lph->linear.size(),
                  sub.lph->parabolic.size(), sub.lph->hyperbolic.size());
  std::printf("\n%-12s %10s %10s %10s %10s %10s %10s\n", "subproblems", "processed", "empty", "split", "solution",
              "search [s]", "wall [s]");
  std::printf("%-12zu %10ld %10ld %10ld %10ld %10.3f %10.3f\n", r.subproblems.size(), r.total.processed,
              r.total.empty, r.total.split, r.total.solution, r.total.seconds, r.seconds);
  std::printf("\n%s\n", r.complete ? "complete: every box of the domain was processed"
                                    : ("INCOMPLETE (" + r.stop_reason + "): results cover only what was explored").c_str());
  const auto names = f.output_names();
  size_t shown = 0, total = 0;
  for (auto& s : r.subproblems) total += s.solutions.size();
  if (total) std::printf("\nsolution boxes (%s, midpoints):\n", f.outputs_are_angles() ? "radians" : "values");
  for (auto& s : r.subproblems)
    for (auto& b : s.solutions) {
      if (shown++ == 20) {
        std::printf("  ... %zu more in the JSON output\n", total - 20);
        goto done;
      }
      Box out = f.to_output(s.index, b);
      std::printf("  [%s]", s.label.c_str());
      for (size_t i = 0; i < out.size(); ++i) std::printf(" %s=%+.6f", names[i].c_str(), median(out[i]));
      std::printf("  (width %.1e)\n", max_width(out));
    }
done:;
}

int run_solve(const SolveArgs& a) {
  io::LoadedCase c = io::load_case(a.case_file);
  solve::RunOptions o;
  o.params.sigma = a.sigma;
  o.params.rho = a.rho;
  o.params.order = a.order == "bfs" ? solve::Order::breadth_first : solve::Order::depth_first;
  o.params.time_limit = a.time_limit;
  o.params.max_boxes = a.max_boxes;
  o.strategy.contractors = prune::parse_strategy_list(a.prune);
  o.strategy.lp = a.lp;
  o.strategy.rigorous = a.arith == "verified";
  o.threads = a.threads;
  o.progress = !a.quiet;
  solve::CaseResult r = solve::solve_case(*c.formulation, o);
  print_summary(c, o, r);
  nlohmann::json j = io::result_json(c.name, c.file, *c.formulation, o, r);
  if (!a.no_verify) {
    verify::VerifyReport v = verify::verify_case(*c.formulation, r);
    print_roots(c, v);
    io::add_verification(j, *c.formulation, v);
  }
  if (!a.json_out.empty()) {
    std::ofstream out(a.json_out);
    if (!out) throw std::runtime_error("cannot write " + a.json_out);
    out << j.dump(1) << '\n';
  }
  return 0;
}

int run_check(const CheckArgs& a) {
  std::ifstream in(a.result_file);
  if (!in) throw std::invalid_argument("cannot read " + a.result_file);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(a.result_file + ": not a linkbox result: " + e.what());
  }
  if (!j.contains("clusters")) throw std::invalid_argument(a.result_file + ": no certificates (was it run with --no-verify?)");
  io::LoadedCase c = io::load_case(a.case_file.empty() ? j.at("case_file").get<std::string>() : a.case_file);
  io::CheckOutcome out;
  try {
    out = io::check_certificates(j, *c.formulation);
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(a.result_file + ": malformed certificate data: " + e.what());
  }
  for (auto& f : out.failures) std::fprintf(stderr, "FAILED: %s\n", f.c_str());
  if (!out.failures.empty()) {
    std::fprintf(stderr, "%zu of the certificates in %s do not hold\n", out.failures.size(), a.result_file.c_str());
    return 1;
  }
  std::printf("%d certificates re-checked from %s and %s: all hold (%s)\n", out.checked, a.result_file.c_str(),
              c.file.c_str(), j.value("headline", "").c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"linkbox: verified position analysis of linkages by interval branch-and-prune"};
  app.require_subcommand(1);
  SolveArgs sa;
  auto* solve_cmd = app.add_subcommand("solve", "enclose every root of a case in solution boxes");
  solve_cmd->add_option("case", sa.case_file, "case file (TOML)")->required();
  solve_cmd->add_option("--sigma", sa.sigma, "solution box size")->check(CLI::PositiveNumber);
  solve_cmd->add_option("--rho", sa.rho, "split when volume ratio after a shrink exceeds rho")
      ->check(CLI::Range(0.0, 1.0));
  solve_cmd->add_option("--order", sa.order, "dfs or bfs")->check(CLI::IsMember({"dfs", "bfs"}));
  solve_cmd->add_option("--prune", sa.prune, "comma-separated contractors, e.g. trapezoid");
  solve_cmd->add_option("--lp", sa.lp, "LP backend: safe or exact")->check(CLI::IsMember({"safe", "exact"}));
  solve_cmd->add_option("--arith", sa.arith, "verified (default) or float: the UNVERIFIED float variant, for comparison")
      ->check(CLI::IsMember({"verified", "float"}));
  solve_cmd->add_option("--time-limit", sa.time_limit, "seconds (0 = none)")->check(CLI::NonNegativeNumber);
  solve_cmd->add_option("--max-boxes", sa.max_boxes, "processed boxes (0 = none)")->check(CLI::NonNegativeNumber);
  solve_cmd->add_option("--threads", sa.threads, "threads across sub-problems")->check(CLI::Range(1, 256));
  solve_cmd->add_option("--json", sa.json_out, "write the result as JSON");
  solve_cmd->add_flag("--quiet", sa.quiet, "no progress on stderr");
  solve_cmd->add_flag("--no-verify", sa.no_verify, "skip clustering and certification");
  CheckArgs ca;
  auto* check_cmd = app.add_subcommand("check", "re-check every certificate of a result JSON (no search)");
  check_cmd->add_option("result", ca.result_file, "JSON written by solve --json")->required();
  check_cmd->add_option("--case", ca.case_file, "case file (default: the one named in the JSON)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  try {
    if (*solve_cmd) return run_solve(sa);
    if (*check_cmd) return run_check(ca);
  } catch (const io::CaseError& e) {
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
