#pragma once
// JSON of the verification stage, and the re-check of its certificates (`linkbox check`).
#include "formulate/formulation.hpp"
#include "verify/certify_case.hpp"

#include <nlohmann/json_fwd.hpp>

namespace linkbox::io {

// Adds `certified_roots`, `headline`, `verification` and `clusters` to a result JSON.
void add_verification(nlohmann::json& result, const formulate::Formulation& formulation,
                      const verify::VerifyReport& report);

struct CheckOutcome {
  int checked = 0;
  std::vector<std::string> failures;  // empty: every certificate holds
};

// Re-runs every certificate of a result JSON against the case's equations alone.
CheckOutcome check_certificates(const nlohmann::json& result, const formulate::Formulation& formulation);

}  // namespace linkbox::io
