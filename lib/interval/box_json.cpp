#include "interval/box_json.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <stdexcept>

namespace linkbox {

nlohmann::json exact_json(double x) {
  if (std::isfinite(x)) return x;
  return std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf");
}

double exact_double(const nlohmann::json& j) {
  if (j.is_number()) return j.get<double>();
  if (!j.is_string()) throw std::invalid_argument("not a number: " + j.dump());
  const std::string s = j.get<std::string>();
  if (s == "inf") return INFINITY;
  if (s == "-inf") return -INFINITY;
  if (s == "nan") return NAN;
  throw std::invalid_argument("not a number: " + s);
}

nlohmann::json exact_json(const Box& b) {
  nlohmann::json j = nlohmann::json::array();
  for (auto& x : b) j.push_back({exact_json(x.lower()), exact_json(x.upper())});
  return j;
}

Box exact_box(const nlohmann::json& j) {
  Box b;
  for (auto& x : j) {
    const double lo = exact_double(x.at(0)), hi = exact_double(x.at(1));
    if (!(lo <= hi)) throw std::invalid_argument("an empty interval");
    b.emplace_back(lo, hi);
  }
  return b;
}

}  // namespace linkbox
