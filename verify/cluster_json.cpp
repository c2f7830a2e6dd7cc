#include "verify/cluster_json.hpp"

#include "interval/box_json.hpp"
#include "verify/curve_map_json.hpp"

#include <nlohmann/json.hpp>

#include <stdexcept>

namespace linkbox::verify {

using nlohmann::json;

namespace {

json doubles_json(const std::vector<double>& xs) {
  json j = json::array();
  for (double x : xs) j.push_back(exact_json(x));
  return j;
}
std::vector<double> doubles_from(const json& j) {
  std::vector<double> xs;
  for (auto& x : j) xs.push_back(exact_double(x));
  return xs;
}

template <class E>
E enum_from(const json& j, int count) {
  const int v = j.get<int>();
  if (v < 0 || v >= count) throw std::invalid_argument("an enumeration value out of range: " + j.dump());
  return static_cast<E>(v);
}

json certificate_json(const newton::Certificate& c) {
  const Eigen::MatrixXd& p = c.preconditioner;
  return {{"status", static_cast<int>(c.status)},
          {"reason", static_cast<int>(c.reason)},
          {"method", static_cast<int>(c.method)},
          {"box", exact_json(c.box)},
          {"image", exact_json(c.image)},
          {"preconditioner", {p.rows(), p.cols(), doubles_json(std::vector<double>(p.data(), p.data() + p.size()))}},
          {"point", doubles_json(c.point)},
          {"flags", {c.on_domain_boundary, c.root_in_domain, c.unique_in_hull}},
          {"fixed_variable", c.fixed_variable}};
}
newton::Certificate certificate_from(const json& j) {
  newton::Certificate c;
  c.status = enum_from<newton::Status>(j.at("status"), 2);
  c.reason = enum_from<newton::Reason>(j.at("reason"), static_cast<int>(newton::Reason::no_root) + 1);
  c.method = enum_from<newton::Method>(j.at("method"), 2);
  c.box = exact_box(j.at("box"));
  c.image = exact_box(j.at("image"));
  const json& p = j.at("preconditioner");
  const long rows = p.at(0), cols = p.at(1);
  const std::vector<double> data = doubles_from(p.at(2));
  if (rows < 0 || cols < 0 || static_cast<size_t>(rows * cols) != data.size())
    throw std::invalid_argument("a preconditioner whose size does not match its entries");
  c.preconditioner = Eigen::Map<const Eigen::MatrixXd>(data.data(), rows, cols);
  c.point = doubles_from(j.at("point"));
  const json& flags = j.at("flags");
  c.on_domain_boundary = flags.at(0);
  c.root_in_domain = flags.at(1);
  c.unique_in_hull = flags.at(2);
  c.fixed_variable = j.at("fixed_variable");
  return c;
}

}  // namespace

json task_json(const ClusterTask& t) {
  json outputs = json::array();
  for (auto& b : t.outputs) outputs.push_back(exact_json(b));
  return {{"boxes", t.boxes}, {"outputs", outputs}, {"residuals", doubles_json(t.residuals)}};
}

ClusterTask task_from(const json& j) {
  ClusterTask t;
  t.boxes = j.at("boxes").get<std::vector<std::pair<size_t, size_t>>>();
  for (auto& b : j.at("outputs")) t.outputs.push_back(exact_box(b));
  t.residuals = doubles_from(j.at("residuals"));
  if (t.outputs.empty() || t.outputs.size() != t.boxes.size() || t.residuals.size() != t.boxes.size())
    throw std::invalid_argument("a cluster task whose members do not match");
  return t;
}

json report_json(const ClusterReport& c) {
  json outputs = json::array();
  for (auto& m : c.outputs) {
    json rows = json::array();
    for (auto& row : m.rows) rows.push_back(exact_json(row));
    outputs.push_back({m.name, rows});
  }
  json crossings = json::array();
  for (auto& x : c.crossings)
    crossings.push_back({x.box, x.chart, certificate_json(x.certificate), x.dropped_equations});
  return {{"status", static_cast<int>(c.status)},
          {"reason", c.reason},
          {"boxes", c.boxes},
          {"hull", exact_json(c.hull)},
          {"chart", c.chart},
          {"certificate", certificate_json(c.certificate)},
          {"subsystem", c.subsystem},
          {"argument", c.argument},
          {"excluding_equation", c.excluding_equation},
          {"root", exact_json(c.root)},
          {"outputs", outputs},
          {"crossings", crossings},
          {"crossings_certified", c.crossings_certified},
          {"duplicate_of", c.duplicate_of},
          {"inequality", c.inequality},
          {"straddled", c.straddled},
          {"exact_root", c.exact_root},
          {"max_residual", exact_json(c.max_residual)},
          {"distances", doubles_json(c.distances)},
          {"max_distance", exact_json(c.max_distance)},
          {"map", c.map ? map_json(*c.map) : json()}};
}

ClusterReport report_from(const json& j) {
  ClusterReport c;
  c.status = enum_from<ClusterStatus>(j.at("status"), static_cast<int>(ClusterStatus::infeasible) + 1);
  c.reason = j.at("reason");
  c.boxes = j.at("boxes").get<std::vector<std::pair<size_t, size_t>>>();
  c.hull = exact_box(j.at("hull"));
  c.chart = j.at("chart");
  c.certificate = certificate_from(j.at("certificate"));
  c.subsystem = j.at("subsystem").get<std::vector<int>>();
  c.argument = j.value("argument", "");
  c.excluding_equation = j.at("excluding_equation");
  c.root = exact_box(j.at("root"));
  for (auto& m : j.at("outputs")) {
    formulate::MatrixOutput out;
    out.name = m.at(0);
    for (auto& row : m.at(1)) out.rows.push_back(exact_box(row));
    c.outputs.push_back(std::move(out));
  }
  for (auto& x : j.at("crossings"))
    c.crossings.push_back({x.at(0).get<size_t>(), x.at(1).get<std::uint64_t>(), certificate_from(x.at(2)),
                           x.at(3).get<std::vector<int>>()});
  c.crossings_certified = j.at("crossings_certified");
  c.duplicate_of = j.at("duplicate_of");
  c.inequality = j.at("inequality");
  c.straddled = j.at("straddled").get<std::vector<int>>();
  c.exact_root = j.at("exact_root").get<std::vector<std::string>>();
  c.max_residual = exact_double(j.at("max_residual"));
  c.distances = doubles_from(j.at("distances"));
  c.max_distance = exact_double(j.at("max_distance"));
  if (!j.at("map").is_null()) c.map = map_from(j.at("map"));
  return c;
}

}  // namespace linkbox::verify
