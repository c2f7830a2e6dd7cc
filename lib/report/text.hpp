#pragma once
// The text a `linkbox solve` run prints: the search summary, then what verification proved.
#include "formulate/load.hpp"
#include "solve/solve_case.hpp"
#include "verify/cluster_report.hpp"

#include <cstdio>

namespace linkbox::report {

// `json_written`: the run writes a JSON, which lists the solution boxes the summary leaves out.
void print_summary(std::FILE* out, const formulate::LoadedCase& c, const solve::RunOptions& o,
                   const solve::CaseResult& r, bool json_written);
void print_verification(std::FILE* out, const formulate::LoadedCase& c, const verify::VerifyReport& v);

}  // namespace linkbox::report
