#pragma once
// The text a `linkbox solve` run prints: the search summary, then what verification proved.
#include "formulate/load.hpp"
#include "solve/solve_case.hpp"
#include "verify/cluster_report.hpp"

#include <cstdio>

namespace linkbox::report {

void print_summary(std::FILE* out, const formulate::LoadedCase& c, const solve::RunOptions& o,
                   const solve::CaseResult& r);
void print_verification(std::FILE* out, const formulate::LoadedCase& c, const verify::VerifyReport& v);

}  // namespace linkbox::report
