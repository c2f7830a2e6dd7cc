#pragma once
// Recording the LPs a search solves, for the soundness oracle (tests/test_lp_oracle.cpp,
// papers/porta-iterated-lp/lp_oracle.py): with LINKBOX_LP_RECORD=<file> in the environment,
// make_lp_solver wraps every backend in a recorder that appends each loaded LP, its column
// bound updates and each min/max with the backend's answer to <file>. Doubles are written
// in hexadecimal, so the LPs read back bit for bit. LINKBOX_LP_RECORD_EVERY=<k> keeps only
// every k-th loaded LP of each solver (default 1).
#include "prune/lp/lp_solver.hpp"

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace linkbox::prune::lp {

// One min or max as the backend under test answered it, on the LP as it stood then.
struct RecordedSolve {
  int col = 0;
  double sense = 1;  // +1: minimize x[col], -1: maximize
  LpBound answer;
  std::vector<double> col_lo, col_hi;  // the column bounds at the time of the solve
};

struct RecordedLp {
  std::string backend;
  LinearProgram program;  // as loaded (its column bounds are those of the load)
  std::vector<RecordedSolve> solves;
};

// Wraps `inner` in a recorder when LINKBOX_LP_RECORD is set; returns `inner` otherwise.
std::unique_ptr<LpSolver> record_if_asked(std::unique_ptr<LpSolver> inner);

// Reads a record file; stops after `limit` LPs (0: all). Throws std::runtime_error on a
// malformed file.
std::vector<RecordedLp> read_lp_record(const std::string& path, size_t limit = 0);

}  // namespace linkbox::prune::lp
