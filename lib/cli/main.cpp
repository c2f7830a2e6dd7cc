// The `linkbox` executable: parses arguments and calls the library. Exit codes: 0 success,
// 1 internal failure, 2 bad input (case file or arguments).
#include "io/case_file.hpp"
#include "io/result_json.hpp"
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
  std::string order = "dfs", prune = "trapezoid", lp = "safe", json_out;
  double time_limit = 0;
  long max_boxes = 0;
  int threads = 1;
  bool quiet = false;
};

void print_summary(const io::LoadedCase& c, const solve::RunOptions& o, const solve::CaseResult& r) {
  const auto& f = *c.formulation;
  std::printf("case      %s (%s, %s)\n", c.name.c_str(), c.kind.c_str(), c.file.c_str());
  std::string prune;
  for (auto& n : r.contractor_names) prune += (prune.empty() ? "" : ",") + n;
  std::printf("strategy  prune=%s sigma=%g rho=%g order=%s threads=%d\n", prune.c_str(), o.params.sigma,
              o.params.rho, o.params.order == solve::Order::depth_first ? "dfs" : "bfs", o.threads);
  std::printf("\n%-12s %10s %10s %10s %10s %10s %10s\n", "subproblems", "processed", "empty", "split", "solution",
              "cpu [s]", "wall [s]");
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
  o.threads = a.threads;
  o.progress = !a.quiet;
  solve::CaseResult r = solve::solve_case(*c.formulation, o);
  print_summary(c, o, r);
  if (!a.json_out.empty()) {
    std::ofstream out(a.json_out);
    if (!out) throw std::runtime_error("cannot write " + a.json_out);
    out << io::result_json(c.name, c.file, *c.formulation, o, r).dump(1) << '\n';
  }
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
  solve_cmd->add_option("--time-limit", sa.time_limit, "seconds (0 = none)")->check(CLI::NonNegativeNumber);
  solve_cmd->add_option("--max-boxes", sa.max_boxes, "processed boxes (0 = none)")->check(CLI::NonNegativeNumber);
  solve_cmd->add_option("--threads", sa.threads, "threads across sub-problems")->check(CLI::Range(1, 256));
  solve_cmd->add_option("--json", sa.json_out, "write the result as JSON");
  solve_cmd->add_flag("--quiet", sa.quiet, "no progress on stderr");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  try {
    if (*solve_cmd) return run_solve(sa);
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
