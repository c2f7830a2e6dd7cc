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

CheckOutcome check_certificates(const nlohmann::json& result, const formulate::Formulation& formulation);

}  // namespace linkbox::verify
