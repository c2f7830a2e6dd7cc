#pragma once
// The claims a result states on top of its certificates (the headline, `exact`, the counts,
// `roots`), recomputed from what `linkbox check` re-proved, and the fields it takes on trust.
#include "formulate/formulation.hpp"
#include "verify/cluster_report.hpp"

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <vector>

namespace linkbox::verify {

// Top-level keys of a result that no check recomputes, each with why: the search's own
// account of itself (completeness needs a search log), its settings, and its figures.
struct TrustedField {
  const char* key;
  const char* why;
};
const std::vector<TrustedField>& trusted_fields();

// Appends to `failures` every claim of `result` that differs from what `clusters` give:
// `clusters` are the result's clusters as re-proved (status, unique_in_hull, duplicate_of,
// root, and a curve's map as re-proved, absent when it was not).
void check_claims(const nlohmann::json& result, const formulate::Formulation& f, std::vector<ClusterReport> clusters,
                  std::vector<std::string>& failures);

}  // namespace linkbox::verify
