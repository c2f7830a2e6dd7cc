#pragma once
// `linkbox check`: re-runs every certificate of a result JSON against the case's equations
// alone, trusting nothing the search or its float steps computed.
#include "formulate/formulation.hpp"

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <vector>

namespace linkbox::verify {

struct CheckOutcome {
  int checked = 0;
  std::vector<std::string> failures;  // empty: every certificate holds
};

// `case_sha256`: the digest of the case file's bytes (input/case_hash.hpp); when given, a
// result whose `case_sha256` differs is "not the case that was solved".
CheckOutcome check_certificates(const nlohmann::json& result, const formulate::Formulation& formulation,
                                const std::string& case_sha256 = {});

}  // namespace linkbox::verify
