#pragma once
// Doubles and boxes as JSON, exactly: what one process writes another reads back bit for bit
// (checkpoints, MPI messages). nlohmann writes the shortest representation that round-trips;
// JSON has no infinities or NaN, so those travel as the strings "inf", "-inf", "nan".
#include "interval/box.hpp"

#include <nlohmann/json_fwd.hpp>

namespace linkbox {

nlohmann::json exact_json(double x);
double exact_double(const nlohmann::json& j);  // std::invalid_argument on anything else

nlohmann::json exact_json(const Box& b);        // [[lo, hi], ...]
Box exact_box(const nlohmann::json& j);         // std::invalid_argument on an empty interval

}  // namespace linkbox
