#pragma once
// One search over the processes of an MPI job: `mpirun -np N linkbox solve CASE`.
//
// Every rank loads the case and runs --threads search slots (slots.hpp); rank 0 also
// coordinates (coordinator.hpp, in its main thread, which does all the MPI calls of its
// process, as on every rank). Slots that run dry ask rank 0 for work: whole sub-problems
// first, then boxes taken from a running search (its oldest pending box, the largest subtree
// in depth-first order, with its place in the tree and its LP backoff). A sub-problem whose
// boxes went to several slots is finished (merged in search-tree order, refined) once every
// piece is back, so the result is the one process's. A racing sub-problem ("auto" with
// several candidates) is not split: the race decides by the order in which one search meets
// its boxes.
//
// Limits: rank 0 sums the boxes every rank reports and tells all to stop; a time limit or an
// interrupt stops each rank by itself and rank 0 is told. Every pending box comes back.
// Faults: a rank silent for longer than LINKBOX_MPI_TIMEOUT seconds (default 60), or an MPI
// error, ends the job with a message and exit code kFaultExit.
#include "distributed/wire.hpp"
#include "formulate/formulation.hpp"
#include "solve/solve_case.hpp"

#include <optional>
#include <stdexcept>
#include <string>

namespace linkbox::distributed {

struct Figures {  // what the distribution cost, for the report (rank 0)
  int ranks = 1;
  int slots = 1;          // per rank
  Traffic traffic;        // summed over the ranks
  long units = 0;         // work handed out: sub-problems, subtrees, finishes
  long steals = 0;        // boxes asked of a running search
  long boxes_given = 0;   // and given
  long boxes = 0;         // processed over the ranks
  long handled = 0;       // messages rank 0's main thread handled (its own slots' too)
  double handling_seconds = 0;  // and the time it took: the coordinator's cost per message
  long clusters = 0;            // verification (mpi_verify.hpp): clusters formed
  long clusters_elsewhere = 0;  // and verified on a rank other than 0
  Traffic verify_traffic;       // its messages, summed over the ranks
  nlohmann::json json() const;
};

// An error in a rank's search (bad input found late, an internal failure), thrown on rank 0
// with the text the CLI prints and its exit code.
struct Failed : std::runtime_error {
  int code;
  Failed(int code, const std::string& text) : std::runtime_error(text), code(code) {}
};
// Thrown on the other ranks after such an error: they leave with the same code, silently.
struct Ended {
  int code;
};

// Rank 0: the run's result, as solve_case gives it, and the figures. Other ranks: nothing.
// An error in any rank's search is thrown on rank 0 (std::invalid_argument for bad input).
std::optional<solve::CaseResult> solve_distributed(const formulate::Formulation& formulation,
                                                   const solve::RunOptions& options, const World& world,
                                                   Figures* figures);

}  // namespace linkbox::distributed
