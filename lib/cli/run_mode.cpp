#include "cli/run_mode.hpp"

#include "cli/ending.hpp"
#include "cli/interrupts.hpp"
#include "report/json.hpp"
#include "report/text.hpp"
#include "solve/output_file.hpp"

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

namespace linkbox::cli {

namespace {

void write_tree(const std::string& path, solve::BoxLog& log) {
  std::string csv = "subproblem,candidate,path,outcome,seconds\n";
  for (auto& e : log.take()) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.4g", e.seconds);
    csv += std::to_string(e.subproblem) + ',' + std::to_string(e.candidate) + ',' + e.path + ',' + e.outcome + ',' +
           seconds + '\n';
  }
  solve::write_output(path, csv);
}

}  // namespace

int RunMode::solve(const SolveCommand& cmd, const formulate::LoadedCase& c) const {
  solve::BoxLog log;
  solve::RunOptions options = cmd.options;
  if (!cmd.record_tree.empty()) options.box_log = &log;
  const solve::CaseResult r = solve::solve_case(*c.formulation, options);
  if (!cmd.record_tree.empty()) write_tree(cmd.record_tree, log);
  return report(
      cmd, c, r, [] { return nlohmann::json::object(); },
      [&](bool verifying, const verify::VerifyOptions& vo) {
        return verifying ? std::optional(verify::verify_case(*c.formulation, r, vo)) : std::nullopt;
      });
}

int RunMode::internal_error() const {
  try {
    throw;
  } catch (const std::exception& e) {
    if (speaks()) std::fprintf(stderr, "linkbox: internal error: %s\n", e.what());
  }
  return 1;
}

namespace {
std::error_code ignored;
}

int RunMode::report(const SolveCommand& cmd, const formulate::LoadedCase& c, const solve::CaseResult& r,
                    const std::function<nlohmann::json()>& extra, const Verifier& verifier) const {
  const solve::RunOptions& o = cmd.options;
  // `--json -` puts the JSON on standard output, alone: the summary goes to stderr.
  std::FILE* text = cmd.json_out == "-" ? stderr : stdout;
  report::print_summary(text, c, o, r, !cmd.json_out.empty());
  std::fflush(text);  // before verification's progress lines on stderr
  nlohmann::json j = report::result_json(c.name, c.file, *c.formulation, o, r);
  j.update(extra());
  const std::string& checkpoint = cmd.checkpoint.empty() ? cmd.kept_checkpoint : cmd.checkpoint;
  // A refinement a limit stopped is done again on resuming (solve/subproblem.cpp).
  const bool final = r.complete && r.unrefined == 0;
  if (final && !cmd.kept_checkpoint.empty()) std::filesystem::remove(cmd.kept_checkpoint, ignored);
  if (!final && !checkpoint.empty()) j["checkpoint"] = checkpoint;  // what `linkbox resume OUT` reads
  // mpirun answers an interrupt with SIGTERM to every rank and SIGKILL a second later: the
  // search's result is on disk before verification starts, and replaced once it is verified.
  if (distributed() && interrupts().load() && !cmd.json_out.empty() && cmd.json_out != "-")
    solve::write_output(cmd.json_out, j.dump(1) + '\n');
  std::optional<verify::VerifyReport> v;
  if (!cmd.no_verify) v = verifier(interrupts().load() < 2, verify_options(cmd));
  if (v) {
    report::print_verification(text, c, *v);
    report::add_verification(j, *c.formulation, *v);
    j.update(extra());
  }
  if (!cmd.json_out.empty()) solve::write_output(cmd.json_out, j.dump(1) + '\n');
  std::fflush(text);
  return end_of_run(cmd, c, r, v ? &*v : nullptr, speaks());
}

}  // namespace linkbox::cli
