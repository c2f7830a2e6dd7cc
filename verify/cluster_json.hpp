#pragma once
// Cluster tasks and reports as JSON, exactly (every double bit for bit, infinities too), so a
// cluster verified by another process reads back as the report this one would have made
// (distributed/ spreads verification over MPI ranks). Not the result file's format: that is
// report/json.hpp, which writes for readers, not for a round trip.
#include "verify/certify_case.hpp"

#include <nlohmann/json_fwd.hpp>

namespace linkbox::verify {

nlohmann::json task_json(const ClusterTask& task);
ClusterTask task_from(const nlohmann::json& j);

nlohmann::json report_json(const ClusterReport& report);
// std::invalid_argument or nlohmann::json::exception on a malformed report.
ClusterReport report_from(const nlohmann::json& j);

}  // namespace linkbox::verify
