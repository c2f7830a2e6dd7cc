#pragma once
// How this process runs a case: alone (RunMode itself), or as one rank of an MPI job. The
// executable decides which can be: `linkbox` compiles run_local.cpp, `linkbox-mpi` (LINKBOX_MPI)
// run_mpi.cpp, and both define start_run_mode.
#include "cli/solve_command.hpp"
#include "formulate/load.hpp"
#include "solve/result.hpp"
#include "verify/certify_case.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <optional>

namespace linkbox::cli {

class RunMode {
 public:
  virtual ~RunMode() = default;
  virtual bool distributed() const { return false; }  // one of several processes of an MPI job
  // Prints the summary and the errors: under mpirun rank 0 does; the others work silently.
  virtual bool speaks() const { return true; }
  // Searches, verifies and reports a loaded case whose settings are resolved; the exit code.
  virtual int solve(const SolveCommand& cmd, const formulate::LoadedCase& c) const;
  // Called while an exception that is not bad input is handled: says what failed, returns the
  // exit code.
  virtual int internal_error() const;

 protected:
  // Runs verification: `verifying` false (a second interrupt) skips it, and returns nothing.
  using Verifier = std::function<std::optional<verify::VerifyReport>(bool verifying, const verify::VerifyOptions&)>;
  // A search's result to the summary and the JSON, then verification (unless --no-verify).
  // `extra` goes into the JSON, asked each time it is written.
  int report(const SolveCommand& cmd, const formulate::LoadedCase& c, const solve::CaseResult& r,
             const std::function<nlohmann::json()>& extra, const Verifier& verifier) const;
};

// Called once, first thing in main: joins the MPI job when mpirun started this process.
std::unique_ptr<RunMode> start_run_mode(int* argc, char*** argv);

}  // namespace linkbox::cli
