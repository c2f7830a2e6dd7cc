// The `linkbox` executable: arguments -> options -> load -> solve -> verify -> report.
// Exit codes: cli/ending.hpp (and docs/cli.md).
#include "cli/ending.hpp"
#include "cli/interrupts.hpp"
#include "cli/run_mode.hpp"
#include "cli/solve_command.hpp"
#include "cli/usage.hpp"
#include "formulate/load.hpp"
#include "input/input_error.hpp"
#include "input/to_toml.hpp"
#include "input/case_hash.hpp"
#include "prune/lp/openblas.hpp"
#include "verify/check.hpp"
#include "verify/check_claims.hpp"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <malloc.h>
#include <sstream>
#include <unistd.h>

using namespace linkbox;

namespace {

// The footer of every help text.
constexpr char kExitCodes[] =
  "Exit codes: 0 complete, every cluster settled (an exact count); 4 complete, some cluster or\n"
  "curve map unresolved; 5 incomplete (a time or box limit); 128+N stopped by signal N (130\n"
  "Ctrl-C); 2 bad input or usage; 1 internal error; 3 a failed MPI job. Unless 0, the last line\n"
  "on stderr says what to try next.";

struct CheckCommand {
  std::string result_file, case_file;
};

void print_trusted(const nlohmann::json& j) {
  std::printf("taken from the result, not re-checked:");
  for (auto& t : verify::trusted_fields())
    if (j.contains(t.key) || std::strchr(t.key, '.')) std::printf(" %s", t.key);
  std::printf(" (the search's completeness needs a log of the search; the rest are settings and figures)\n");
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
  const std::string case_file = cmd.case_file.empty() ? cli::found_beside(j.at("case_file").get<std::string>(), cmd.result_file)
                                                     : cmd.case_file;
  const formulate::LoadedCase c = formulate::load_case(case_file);
  verify::CheckOutcome out;
  try {
    out = verify::check_certificates(j, *c.formulation, input::case_sha256(case_file));
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(cmd.result_file + ": malformed certificate data: " + e.what());
  }
  for (auto& f : out.failures) std::fprintf(stderr, "FAILED: %s\n", f.c_str());
  if (!out.failures.empty()) {
    std::fprintf(stderr, "%zu of the claims in %s do not hold\n", out.failures.size(), cmd.result_file.c_str());
    return cli::exit_failed;
  }
  std::printf("%d certificates re-checked from %s and %s, and the headline, counts and roots recomputed: all hold (%s)\n",
              out.checked, cmd.result_file.c_str(), c.file.c_str(), j.value("headline", "").c_str());
  print_trusted(j);
  return 0;
}

// The subcommands, their arguments filled in by the parse.
struct Commands {
  cli::SolveCommand solve, resume;
  CheckCommand check;
  std::string convert_file;
  CLI::App *solve_app, *resume_app, *check_app, *convert_app;
};

void add_solve(CLI::App& app, Commands& c) {
  c.solve_app = app.add_subcommand("solve", "enclose every root of a case in solution boxes");
  c.solve_app->add_option("case", c.solve.case_file, "case file (TOML; or a peer's .bch or .cuik)")
      ->required()
      ->type_name("CASE");
  cli::add_solve_flags(*c.solve_app, c.solve);
  c.solve_app->footer(std::string(R"(Examples:
  linkbox solve cases/linkages/6r-rigid.toml
  linkbox solve cases/linkages/cyclohexane.toml --prune lp --json out.json
  linkbox solve cases/benchmarks/eco9.bch --time-limit 60 --checkpoint eco9.ckpt
  linkbox solve case.toml --arith float        (unverified, for comparison)
Settings come from the flags, else the case's [solve] table, else the defaults; the summary's
`settings` line says which.
)" + std::string(kExitCodes)));
}

void add_resume(CLI::App& app, Commands& c) {
  c.resume_app = app.add_subcommand(
      "resume", "go on with a run saved by --checkpoint; it ends with the boxes an unbroken run gives");
  c.resume_app->add_option("checkpoint", c.resume.resume, "the checkpoint file")->required()->type_name("CHECKPOINT");
  c.resume_app->add_option("--case", c.resume.case_file, "case file (default: the one named in the checkpoint)")
      ->type_name("CASE");
  cli::add_solve_flags(*c.resume_app, c.resume);
  c.resume_app->footer(std::string(R"(Examples:
  linkbox resume eco9.ckpt
  linkbox resume eco9.ckpt --time-limit 600 --json eco9.json
A checkpoint of another case, or with other search settings, is refused (exit 2).
)" + std::string(kExitCodes)));
}

void add_check_and_convert(CLI::App& app, Commands& c) {
  c.check_app = app.add_subcommand("check", "re-check every certificate of a result JSON (no search)");
  c.check_app->add_option("result", c.check.result_file, "JSON written by solve --json")->required()->type_name("OUT.json");
  c.check_app->add_option("--case", c.check.case_file, "case file (default: the one named in the JSON)")
      ->type_name("CASE");
  c.convert_app = app.add_subcommand("convert", "write a peer's model (Minibex .bch, CuikSuite .cuik) as a TOML case");
  c.convert_app->add_option("model", c.convert_file, "the .bch or .cuik file")->required()->type_name("MODEL");
  c.check_app->footer(R"(Examples:
  linkbox solve cases/spherical/wrist.toml --json wrist.json && linkbox check wrist.json
  linkbox check result.json --case my-copy-of-the-case.toml
Exit 0 when every claim holds, 1 when one does not, 2 when the result or case cannot be read.)");
  c.convert_app->footer(R"(Examples:
  linkbox convert cases/benchmarks/eco9.bch > eco9.toml
  linkbox convert cases/benchmarks/cyclohexan3d.cuik > cyclohexan3d.toml
An unsupported construct is an error naming file:line (exit 2), never a change of meaning.)");
}

int run_command(Commands& c, const cli::RunMode& mode) {
  if (*c.solve_app || *c.resume_app) cli::catch_interrupts();
  if (*c.solve_app) return cli::run_solve(c.solve, mode);
  if (*c.resume_app) return cli::run_solve(c.resume, mode);
  if (*c.check_app) return run_check(c.check);
  if (*c.convert_app) {
    std::fputs(input::convert_to_toml(c.convert_file).c_str(), stdout);
    return 0;
  }
  return 0;
}

// Called while an exception is handled: says what it was (the process that speaks), returns
// the exit code.
int error_exit_code(const cli::RunMode& mode) {
  try {
    throw;
  } catch (const input::InputError& e) {
    if (mode.speaks()) std::fprintf(stderr, "%s\n", e.what());
    return cli::exit_bad_input;
  } catch (const std::invalid_argument& e) {
    if (mode.speaks()) std::fprintf(stderr, "linkbox: %s\n", e.what());
    return cli::exit_bad_input;
  } catch (...) {
    return mode.internal_error();
  }
}

// CLP's LAPACK may be OpenBLAS, whose thread pool busy-waits for work (papers/decisions/
// solve-driver.md); linkbox makes no BLAS calls worth threading. The setting is read at load,
// so set it and start again once; with any other LAPACK a restart only doubles the start-up.
void single_threaded_blas(char** argv) {
  if (std::getenv("OPENBLAS_NUM_THREADS") || !prune::lp::openblas_loaded()) return;
  setenv("OPENBLAS_NUM_THREADS", "1", 1);
  execv("/proc/self/exe", argv);  // returns only on failure: then run as we are
}

// glibc gives the heap's free top back to the system once 128 KiB of it are free, and serves
// blocks from 128 KiB up by mmap: an LP contractor's per-box allocations then move the top up
// and down, a system call and fresh page faults each time. Keeping the heap avoids both.
void keep_heap() {
  mallopt(M_MMAP_THRESHOLD, 16 << 20);
  mallopt(M_TRIM_THRESHOLD, 64 << 20);
}

}  // namespace

int main(int argc, char** argv) {
  single_threaded_blas(argv);
  keep_heap();
  const std::unique_ptr<cli::RunMode> mode = cli::start_run_mode(&argc, &argv);
  CLI::App app{"linkbox: verified position analysis of linkages by interval branch-and-prune", "linkbox"};
  app.set_version_flag("-V,--version", "linkbox " LINKBOX_VERSION);
  app.require_subcommand(1);
  app.footer("Run `linkbox help SUBCOMMAND` (or `linkbox SUBCOMMAND -h`) for its options.\n" + std::string(kExitCodes));
  Commands commands;
  add_solve(app, commands);
  add_resume(app, commands);
  add_check_and_convert(app, commands);
  if (const int code = cli::answer_before_parse(app, argc, argv, mode->speaks()); code >= 0) return code;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::ostringstream silent;
    int code = mode->speaks() ? app.exit(e) : app.exit(e, silent, silent);
    return code == 0 ? cli::exit_exact : cli::exit_bad_input;
  }
  try {
    return run_command(commands, *mode);
  } catch (...) {
    return error_exit_code(*mode);
  }
}
