#pragma once
// The statement a run supports, from the clusters' verdicts: "exactly N roots in the domain,
// each in its certified box" only when the search was complete and rigorous and every
// cluster certified a distinct root; otherwise the counts and why.
#include "solve/result.hpp"
#include "verify/cluster_report.hpp"

namespace linkbox::verify {

// Fills the counts, `exact` and `headline` of `report` from its clusters.
// `overlaps_unresolved`: pairs of certified roots that overlap but could not be proved the
// same root.
void summarise(VerifyReport& report, int overlaps_unresolved, const solve::CaseResult& result);

}  // namespace linkbox::verify
