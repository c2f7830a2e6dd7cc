#pragma once
// How a solve or resume ends: its exit code, and the next command to try when it is not final.
#include "cli/solve_command.hpp"
#include "formulate/load.hpp"
#include "solve/result.hpp"
#include "verify/cluster_report.hpp"

namespace linkbox::cli {

// The exit codes a script can branch on (docs/cli.md); 128 + N after signal N.
enum ExitCode : int {
  exit_exact = 0,          // complete, and every cluster settled: the headline is an exact count
  exit_failed = 1,         // an internal error, or `check` found a claim that does not hold
  exit_bad_input = 2,      // a case file, the arguments, an output or a checkpoint
  exit_mpi_failed = 3,     // under mpirun: a rank went silent or an MPI error ended the run
  exit_unresolved = 4,     // complete, but some cluster or curve map is not settled
  exit_incomplete = 5,     // a time or box limit stopped the search
};

// The exit code of a run that went on to its end, `v` its verification (none with --no-verify
// or after a second interrupt); when it is not exit_exact and `speaks`, prints on stderr one
// line with the next command to try.
int end_of_run(const SolveCommand& cmd, const formulate::LoadedCase& c, const solve::CaseResult& r,
               const verify::VerifyReport* v, bool speaks);

}  // namespace linkbox::cli
