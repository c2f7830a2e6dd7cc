#pragma once
// What `linkbox check` reads from a result's JSON (docs/json.md): boxes, certificates and the
// natural equations a certificate names. Malformed entries throw (nlohmann's errors, or
// std::invalid_argument), which check reports as failures.
#include "model/polynomial.hpp"
#include "newton/certify.hpp"

#include <nlohmann/json_fwd.hpp>

#include <vector>

namespace linkbox::verify {

Box box_from(const nlohmann::json& j);
newton::Certificate certificate_from(const nlohmann::json& j);

// The natural equations a certificate speaks of: those listed under `key`, or all of them.
// Returns false when an index is out of range.
bool equations_named(const nlohmann::json& c, const char* key, const std::vector<model::Polynomial>& all,
                     std::vector<model::Polynomial>& out);

}  // namespace linkbox::verify
