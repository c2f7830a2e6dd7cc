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
  int threads = 1;  // clusters verified in parallel; the report does not depend on it
};

VerifyReport verify_case(const formulate::Formulation& formulation, const solve::CaseResult& result,
                         const VerifyOptions& options = {});

}  // namespace linkbox::verify
