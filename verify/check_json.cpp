#include "verify/check_json.hpp"

#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>

namespace linkbox::verify {

using nlohmann::json;

Box box_from(const json& j) {
  Box b;
  for (auto& x : j) b.push_back(Interval(x.at(0).get<double>(), x.at(1).get<double>()));
  return b;
}

newton::Certificate certificate_from(const json& j) {
  newton::Certificate c;
  const std::string method = j.at("method");
  if (method != "krawczyk" && method != "hansen-sengupta")
    throw std::invalid_argument("unknown certificate method '" + method + "'");
  c.method = method == "krawczyk" ? newton::Method::krawczyk : newton::Method::hansen_sengupta;
  c.box = box_from(j.at("box"));
  // Rows of one length, checked before anything is allocated or written.
  const json& m = j.at("preconditioner");
  const size_t cols = m.empty() ? 0 : m.at(0).size();
  for (size_t r = 0; r < m.size(); ++r)
    if (!m.at(r).is_array() || m[r].size() != cols)
      throw std::invalid_argument("a preconditioner whose rows differ in length");
  c.preconditioner.resize(m.size(), cols);
  for (size_t r = 0; r < m.size(); ++r)
    for (size_t k = 0; k < cols; ++k) c.preconditioner(r, k) = m[r][k].get<double>();
  c.fixed_variable = j.value("fixed_variable", -1);
  return c;
}

bool equations_named(const json& c, const char* key, const std::vector<model::Polynomial>& all,
                     std::vector<model::Polynomial>& out) {
  if (!c.contains(key)) {
    out = all;
    return true;
  }
  out.clear();
  for (auto& r : c.at(key)) {
    const int i = r.get<int>();
    if (i < 0 || i >= static_cast<int>(all.size())) return false;
    out.push_back(all[i]);
  }
  return true;
}

}  // namespace linkbox::verify
