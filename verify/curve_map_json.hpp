#pragma once
// A curve map as JSON, exactly (every double bit for bit): the result file's "map" of a curve
// cluster and the MPI round trip write the same object. An arc is its piece, box, parameter
// and preconditioner (what `linkbox check` re-proves it from) plus the image and ends they give.
#include "verify/curve_map.hpp"

#include <nlohmann/json_fwd.hpp>

namespace linkbox::verify {

nlohmann::json map_json(const CurveMap& map);
// std::invalid_argument or nlohmann::json::exception on a malformed map.
CurveMap map_from(const nlohmann::json& j);

nlohmann::json matrix_json(const Eigen::MatrixXd& m);  // [rows, cols, [entries, column-major]]
Eigen::MatrixXd matrix_from(const nlohmann::json& j);

}  // namespace linkbox::verify
