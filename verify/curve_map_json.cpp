#include "verify/curve_map_json.hpp"

#include "interval/box_json.hpp"

#include <nlohmann/json.hpp>

#include <stdexcept>

namespace linkbox::verify {

using nlohmann::json;

json matrix_json(const Eigen::MatrixXd& m) {
  json data = json::array();
  for (Eigen::Index k = 0; k < m.size(); ++k) data.push_back(exact_json(m.data()[k]));
  return {m.rows(), m.cols(), data};
}

Eigen::MatrixXd matrix_from(const json& j) {
  const long rows = j.at(0), cols = j.at(1);
  const json& data = j.at(2);
  if (rows < 0 || cols < 0 || static_cast<size_t>(rows * cols) != data.size())
    throw std::invalid_argument("a matrix whose size does not match its entries");
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index k = 0; k < m.size(); ++k) m.data()[k] = exact_double(data[k]);
  return m;
}

json map_json(const CurveMap& map) {
  json arcs = json::array();
  for (auto& a : map.arcs) {
    arcs.push_back({{"member", a.member},
                    {"chart", a.chart},
                    {"piece", exact_json(a.piece)},
                    {"box", exact_json(a.arc.box)},
                    {"parameter", a.arc.parameter},
                    {"preconditioner", matrix_json(a.arc.preconditioner)},
                    {"image", exact_json(a.arc.image)},
                    {"ends", {exact_json(a.arc.ends[0]), exact_json(a.arc.ends[1])}}});
    if (!a.dropped.empty()) arcs.back()["dropped_equations"] = a.dropped;
  }
  json components = json::array();
  for (auto& c : map.components)
    components.push_back(
        {{"arcs", c.arcs}, {"closed", c.closed}, {"singular_ends", c.singular_ends}, {"extent", exact_json(c.extent)}});
  json regions = json::array();
  for (auto& r : map.singular_regions) regions.push_back(exact_json(r));
  json unresolved = json::array();
  for (auto& [member, piece] : map.unresolved) unresolved.push_back({{"member", member}, {"piece", exact_json(piece)}});
  json singular = json::array();
  for (auto& p : map.singular_points) {
    json normal = json::array();
    for (double x : p.normal) normal.push_back(exact_json(x));
    singular.push_back({{"chart", p.chart},
                        {"box", exact_json(p.box)},
                        {"preconditioner", matrix_json(p.preconditioner)},
                        {"normal", normal},
                        {"point", p.point},
                        {"kind", to_string(p.kind)},
                        {"branches", p.branches}});
  }
  json out = {{"proved", map.proved},
          {"statement", map.statement},
          {"equations", map.equations},
          {"charts", map.charts},
          {"components", components},
          {"undecided_ends", map.undecided_ends},
          {"loose_ends", map.loose_ends},
          {"unresolved", unresolved},
          {"singular_regions", regions},
          {"singular_points", singular},
          {"arcs", arcs}};
  if (map.subspace_variable >= 0) out["subspace_variable"] = map.subspace_variable;
  if (map.inexact_coefficients) out["inexact_coefficients"] = true;
  return out;
}

CurveMap map_from(const json& j) {
  CurveMap map;
  map.proved = j.at("proved");
  map.statement = j.at("statement");
  map.equations = j.at("equations").get<std::vector<int>>();
  map.subspace_variable = j.value("subspace_variable", -1);
  map.charts = j.at("charts").get<std::vector<std::uint64_t>>();
  for (auto& c : j.at("components"))
    map.components.push_back({c.at("arcs").get<std::vector<size_t>>(), c.at("closed").get<bool>(),
                              c.value("singular_ends", 0), exact_box(c.at("extent"))});
  for (auto& r : j.at("singular_regions")) map.singular_regions.push_back(exact_box(r));
  for (auto& p : j.value("singular_points", json::array())) {
    SingularPoint s;
    s.chart = p.at("chart");
    s.box = exact_box(p.at("box"));
    s.preconditioner = matrix_from(p.at("preconditioner"));
    for (auto& x : p.at("normal")) s.normal.push_back(exact_double(x));
    s.point = p.at("point").get<std::vector<std::string>>();
    const std::string kind = p.at("kind");
    s.kind = kind == "crossing" ? SingularKind::crossing : kind == "isolated" ? SingularKind::isolated : SingularKind::degenerate;
    s.branches = p.at("branches");
    map.singular_points.push_back(std::move(s));
  }
  map.inexact_coefficients = j.value("inexact_coefficients", false);
  map.undecided_ends = j.at("undecided_ends");
  map.loose_ends = j.at("loose_ends");
  for (auto& u : j.at("unresolved")) map.unresolved.emplace_back(u.at("member").get<size_t>(), exact_box(u.at("piece")));
  for (auto& a : j.at("arcs")) {
    MapArc m;
    m.member = a.at("member");
    m.chart = a.at("chart");
    m.piece = exact_box(a.at("piece"));
    m.arc.certified = true;
    m.arc.box = exact_box(a.at("box"));
    m.arc.parameter = a.at("parameter");
    m.arc.preconditioner = matrix_from(a.at("preconditioner"));
    m.arc.image = exact_box(a.at("image"));
    m.arc.ends = {exact_box(a.at("ends").at(0)), exact_box(a.at("ends").at(1))};
    if (a.contains("dropped_equations")) m.dropped = a.at("dropped_equations").get<std::vector<int>>();
    map.arcs.push_back(std::move(m));
  }
  return map;
}

}  // namespace linkbox::verify
