#pragma once
// The JSON written by `linkbox solve --json` (documented in README.md): serialisation only;
// nothing here proves or computes a claim.
#include "formulate/formulation.hpp"
#include "solve/solve_case.hpp"
#include "verify/cluster_report.hpp"

#include <nlohmann/json_fwd.hpp>

namespace linkbox::report {

nlohmann::json interval_json(const Interval& x);  // [lo, hi]
nlohmann::json box_json(const Box& b);            // [[lo, hi], ...]

nlohmann::json result_json(const std::string& case_name, const std::string& case_file,
                           const formulate::Formulation& formulation, const solve::RunOptions& options,
                           const solve::CaseResult& result);

// Adds `certified_roots`, `headline`, `verification` and `clusters` to a result JSON.
void add_verification(nlohmann::json& result, const formulate::Formulation& formulation,
                      const verify::VerifyReport& report);

}  // namespace linkbox::report
