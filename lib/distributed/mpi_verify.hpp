#pragma once
// Verification over the ranks of an MPI job, after solve_distributed. Rank 0 forms the clusters
// and hands them out a few at a time, as each rank's threads free up (itself included, through
// its own inbox); every rank verifies on --threads and sends each cluster's report back as
// exact JSON (verify/cluster_json.hpp). Rank 0 then concludes as verify_case does, so the report
// is verify_case's, bit for bit. Heartbeats and the fault timeout are the search's.
#include "distributed/mpi_solve.hpp"
#include "verify/certify_case.hpp"

namespace linkbox::distributed {

// Every rank calls it, or none (all or none run with --no-verify). Rank 0 passes the result to
// verify, or nullptr to end the phase at once (an interrupted run that skips verification), and
// gets the report; its figures gain the phase's. The other ranks pass nullptr and get nothing.
// A failed cluster throws Failed on rank 0 and Ended on the others, as the search does.
std::optional<verify::VerifyReport> verify_distributed(const formulate::Formulation& formulation,
                                                       const solve::CaseResult* result,
                                                       const verify::VerifyOptions& options, const World& world,
                                                       Figures* figures);

}  // namespace linkbox::distributed
