#pragma once
// `linkbox solve` and `linkbox resume`: their flags, the settings they resolve, and the run.
#include "solve/solve_case.hpp"
#include "verify/certify_case.hpp"

#include <string>

namespace CLI {
class App;
}

namespace linkbox::cli {

class RunMode;

struct SolveCommand {
  std::string case_file, json_out, prune, checkpoint, record_tree;
  solve::RunOptions options;
  bool quiet = false, no_verify = false;
  std::string resume;  // resume: the checkpoint to go on from (or a result naming one)
  // A run with --json OUT and no --checkpoint keeps its state in OUT.ckpt, removed when the
  // run completes; an incomplete result names it (`checkpoint`), so `linkbox resume OUT`
  // goes on from it.
  std::string kept_checkpoint;
  CLI::App* app = nullptr;
  bool given(const char* flag) const;  // on the command line
};

// A file a result names (its case, its checkpoint): as written when it exists there (or is
// absolute), else the same path, or name, in the result's folder (a result moved with it).
std::string found_beside(const std::string& named, const std::string& result_file);

// The flags of both commands, into `s` (s.app is `app`).
void add_solve_flags(CLI::App& app, SolveCommand& s);

// Loads the case, resolves the settings (flags, the case's [solve] table, the defaults; or the
// checkpoint's), then runs and reports it as `mode` does. Returns the exit code.
int run_solve(SolveCommand& cmd, const RunMode& mode);

verify::VerifyOptions verify_options(const SolveCommand& cmd);

}  // namespace linkbox::cli
