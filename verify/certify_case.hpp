#pragma once
// Post-processing of a branch-and-prune run: cluster the solution boxes (in the output
// variables, angles modulo 2 pi, so a root found by two sub-problems is one cluster), then
// certify each cluster's root by interval Newton in the case's natural unknowns, recognise
// curve clusters, and state what was proved.
#include "formulate/formulation.hpp"
#include "solve/result.hpp"
#include "verify/cluster_report.hpp"

#include <functional>
#include <string>
#include <vector>

namespace linkbox::verify {

struct VerifyOptions {
  newton::NewtonOptions newton;
  // Asked before each cluster: when it says so (a second interrupt), the clusters left are
  // reported unverified ("verification skipped") and the run ends at once.
  std::function<bool()> skip_rest;
  // Seconds verification may take (0: no limit): clusters not begun by then are reported
  // unverified ("verification skipped (time limit)"); the one under way finishes.
  double time_limit = 0;
  int threads = 1;  // clusters verified in parallel; the report does not depend on it
  // A line on stderr each second of a verification that takes longer ("linkbox: verifying:
  // 12/32 clusters, 3.1 s"), as the search has.
  bool progress = false;
};

VerifyReport verify_case(const formulate::Formulation& formulation, const solve::CaseResult& result,
                         const VerifyOptions& options = {});

// verify_case in its three steps, for a caller that spreads the clusters over processes
// (distributed/): the clusters, each verified on its own (a pure function of the task), then
// the run's conclusions (duplicate roots merged, the headline). Only the last needs all.
struct ClusterTask {
  std::vector<std::pair<size_t, size_t>> boxes;  // (sub-problem, solution index)
  std::vector<Box> outputs;                      // each member in the output variables
  std::vector<double> residuals;                 // each member's rigorous residual bound
};
std::vector<ClusterTask> cluster_tasks(const formulate::Formulation& formulation, const solve::CaseResult& result,
                                       int threads = 1);
ClusterReport verify_cluster(const formulate::Formulation& formulation, const ClusterTask& task,
                             const VerifyOptions& options);
// The report of a cluster that verification did not reach: its boxes, hull and `why`.
ClusterReport skipped_cluster(const formulate::Formulation& formulation, const ClusterTask& task,
                              const std::string& why);
// `clusters` in the order of cluster_tasks; report.seconds is left to the caller.
VerifyReport conclude(const formulate::Formulation& formulation, std::vector<ClusterReport> clusters,
                      const solve::CaseResult& result, const VerifyOptions& options);

}  // namespace linkbox::verify
