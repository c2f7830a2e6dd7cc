#pragma once
// The JSON written by `linkbox solve --json` (documented in README.md).
#include "formulate/formulation.hpp"
#include "solve/solve_case.hpp"

#include <nlohmann/json_fwd.hpp>

namespace linkbox::io {

nlohmann::json interval_json(const Interval& x);  // [lo, hi]
nlohmann::json box_json(const Box& b);            // [[lo, hi], ...]

nlohmann::json result_json(const std::string& case_name, const std::string& case_file,
                           const formulate::Formulation& formulation, const solve::RunOptions& options,
                           const solve::CaseResult& result);

}  // namespace linkbox::io
