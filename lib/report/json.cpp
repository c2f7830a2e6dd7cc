#include "report/json.hpp"

#include "input/case_hash.hpp"
#include "report/version.hpp"
#include "solve/strategy.hpp"
#include "verify/curve_map_json.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>

namespace linkbox::report {

using nlohmann::json;

json interval_json(const Interval& x) { return json::array({x.lower(), x.upper()}); }

json box_json(const Box& b) {
  json j = json::array();
  for (auto& x : b) j.push_back(interval_json(x));
  return j;
}

namespace {

json stats_json(const solve::Stats& s) {
  return {{"processed", s.processed}, {"empty", s.empty}, {"split", s.split},
          {"solution_boxes", s.solution}, {"certified_in_search", s.certified}, {"certify_calls", s.certify_calls},
          {"shrinks", s.shrinks}, {"seconds", s.seconds}};
}

json parameters_json(const solve::RunOptions& options, const solve::CaseResult& result) {
  const auto& p = options.params;
  return {{"sigma", p.sigma},
          {"rho", p.rho > 0 || result.rho <= 0 ? p.rho : result.rho},  // auto resolved
          {"order", p.order == solve::Order::depth_first ? "dfs" : "bfs"},
          {"prune", options.strategy.prune.text()},
          {"bisect", solve::to_string(options.bisect)},
          {"lp", prune::lp::to_string(options.strategy.lp)},
          {"lp_order", prune::lp::to_string(options.strategy.lp_order)},
          {"arith", to_string(options.strategy.arith)},
          {"time_limit", p.time_limit},
          {"cpu_limit", p.cpu_limit},
          {"narrow", p.narrow},
          {"max_boxes", p.max_boxes},
          {"threads", options.threads},
          // where the settings came from: "flag", "case file", "checkpoint", "symmetric loop"; absent: default
          {"sources", options.setting_source}};
}

json case_stats_json(const solve::CaseResult& result) {
  json stats = stats_json(result.total);
  stats["subproblems"] = result.subproblems.size();
  stats["seconds"] = result.seconds;
  stats["cpu_seconds"] = result.cpu_seconds;  // the search's, every thread (verification not included)
  stats["search_seconds"] = result.total.seconds;  // the winning searches' wall time, summed over sub-problems
  return stats;
}

json contractors_json(const solve::CaseResult& result) {
  json contractors = json::array();
  for (size_t k = 0; k < result.counters.size(); ++k) {
    auto& c = result.counters[k];
    json cj = {{"name", result.contractor_names.at(k)}, {"calls", c.calls}, {"emptied", c.emptied},
               {"volume_removed", c.volume_removed}, {"seconds", c.seconds},
               {"lps_solved", c.lps_solved}, {"lp_iterations", c.lp_iterations},
               {"operations", c.operations}};
    if (c.lps_solved > 0) {
      // The LP contractor's cost: how many LPs a box takes (over every box processed, those
      // it did not run on included) and what one costs (the contractor's seconds, its bound
      // propagation included, per LP).
      const long boxes = std::max<long>(1, result.total.processed);
      cj["lps_per_box"] = static_cast<double>(c.lps_solved) / static_cast<double>(boxes);
      cj["us_per_lp"] = 1e6 * c.seconds / static_cast<double>(c.lps_solved);
    }
    if (c.lp_paths.any())  // the exact LP backend only
      cj["lp_paths"] = {{"basis", c.lp_paths.basis}, {"repaired", c.lp_paths.repaired}, {"farkas", c.lp_paths.farkas},
                        {"fallback", c.lp_paths.fallback}, {"pivots", c.lp_paths.pivots}};
    contractors.push_back(cj);
  }
  return contractors;
}

json subproblem_json(const solve::SubResult& s) {
  json sj = stats_json(s.stats);
  sj["index"] = s.index;
  sj["label"] = s.label;
  sj["equations"] = s.equations;
  sj["variables"] = s.variables;
  sj["complete"] = s.complete;
  sj["volume_left"] = s.volume_left;
  json pending = json::array();  // in the search variables, as `search_box` of a solution
  for (auto& b : s.pending) pending.push_back(box_json(b));
  sj["pending"] = pending;
  return sj;
}

json solution_json(const formulate::Formulation& formulation, const solve::SubResult& s, size_t k) {
  const Box& box = s.solutions[k];
  json sol = {{"subproblem", s.index},
              {"box", box_json(formulation.to_output(s.index, box))},
              {"search_box", box_json(box)},
              {"residual", s.residuals.at(k)},
              {"certified_in_search", k < s.certified.size() && s.certified[k]}};
  for (auto& m : formulation.declared_outputs(s.index, box)) {
    json rows = json::array();
    for (auto& row : m.rows) rows.push_back(box_json(row));
    sol[m.name] = rows;  // e.g. "rotation": 3x3 [lo, hi], row-major
  }
  return sol;
}

}  // namespace

json result_json(const std::string& case_name, const std::string& case_file,
                 const formulate::Formulation& formulation, const solve::RunOptions& options,
                 const solve::CaseResult& result) {
  json j;
  j["format"] = kResultFormat;
  j["linkbox"] = linkbox_version();
  j["case"] = case_name;
  j["case_file"] = case_file;
  j["case_sha256"] = input::case_sha256(case_file);
  j["kind"] = formulation.kind();
  j["variables"] = formulation.output_names();
  j["variables_unit"] = formulation.outputs_are_angles() ? "radians" : "";
  j["parameters"] = parameters_json(options, result);
  // Model size of an L/P/H formulation (iterated-LP paper): primary, dummy, #L, #P, #H.
  if (formulation.subproblem_count() == 1) {
    const auto sub = formulation.subproblem(0);
    if (sub.lph) {
      const auto& m = *sub.lph;
      j["model"] = {{"primary", m.primary.size()}, {"dummy", m.variables.size() - m.primary.size()},
                    {"linear", m.linear.size()}, {"parabolic", m.parabolic.size()}, {"hyperbolic", m.hyperbolic.size()}};
    }
  }
  if (auto notes = formulation.model_notes(); !notes.empty()) j["model_notes"] = notes;  // e.g. what was lifted
  j["strategy"] = result.strategy.text();  // what ran, "auto" resolved
  j["bisect"] = result.bisect;
  if (!result.subproblems.empty() && result.subproblems[0].race.size() > 1) {
    json race = json::array();  // "auto": the candidates raced, each one's work, the winner last
    for (auto& [name, work] : result.subproblems[0].race) race.push_back({{"strategy", name}, {"work", work}});
    j["race"] = race;
  }
  // A race stopped by a limit has no winner, but its choices still say where the work went.
  if (!result.subproblems.empty() && !result.subproblems[0].race_choices.empty())
    j["race_choices"] = result.subproblems[0].race_choices;
  j["complete"] = result.complete;
  if (!result.complete) j["stop_reason"] = result.stop_reason;
  // A complete search whose solution boxes a limit left unrefined: why its count may not be exact.
  if (result.unrefined) j["refinement_stopped"] = {{"reason", result.refine_stop}, {"boxes", result.unrefined}};
  j["pending_boxes"] = result.pending_boxes;
  j["volume_left"] = result.volume_left;  // unexplored share of the domain, averaged over sub-problems
  j["stats"] = case_stats_json(result);
  j["contractors"] = contractors_json(result);
  json subs = json::array(), sols = json::array();
  for (auto& s : result.subproblems) {
    subs.push_back(subproblem_json(s));
    for (size_t k = 0; k < s.solutions.size(); ++k) sols.push_back(solution_json(formulation, s, k));
  }
  j["subproblem_stats"] = subs;
  j["solutions"] = sols;
  return j;
}

namespace {

json matrix_json(const Eigen::MatrixXd& m) {
  json j = json::array();
  for (int r = 0; r < m.rows(); ++r) {
    json row = json::array();
    for (int c = 0; c < m.cols(); ++c) row.push_back(m(r, c));
    j.push_back(row);
  }
  return j;
}

json certificate_json(const newton::Certificate& c) {
  json j = {{"status", c.status == newton::Status::certified ? "certified" : "unverified"},
            {"method", c.method == newton::Method::krawczyk ? "krawczyk" : "hansen-sengupta"},
            {"box", box_json(c.box)},
            {"image", box_json(c.image)},
            {"preconditioner", matrix_json(c.preconditioner)},
            {"unique_in_hull", c.unique_in_hull},
            {"on_domain_boundary", c.on_domain_boundary},
            {"root_in_domain", c.root_in_domain}};
  if (c.status != newton::Status::certified) j["reason"] = newton::to_string(c.reason);
  if (c.fixed_variable >= 0) j["fixed_variable"] = c.fixed_variable;
  return j;
}

json cluster_json(const formulate::Formulation& f, const verify::ClusterReport& c) {
  json cj = {{"status", verify::to_string(c.status)}, {"boxes", c.boxes.size()}, {"hull", box_json(c.hull)},
             {"chart", c.chart}, {"max_residual", c.max_residual}};
  if (!c.reason.empty()) cj["reason"] = c.reason;
  json members = json::array();
  for (auto [s, k] : c.boxes) members.push_back({s, k});
  cj["members"] = members;
  cj["natural_unknowns"] = f.natural(c.chart).unknowns;
  if (c.status == verify::ClusterStatus::certified) {
    cj["root"] = box_json(c.root);
    for (auto& m : c.outputs) {
      json rows = json::array();
      for (auto& row : m.rows) rows.push_back(box_json(row));
      cj[m.name] = rows;
    }
    if (c.duplicate_of >= 0) cj["duplicate_of"] = c.duplicate_of;
    cj["distances"] = c.distances;
    cj["max_distance"] = c.max_distance;
  }
  // Inequalities (natural system): the one violated or sat on, and those left undecided.
  if (c.inequality >= 0) cj["inequality"] = c.inequality;
  if (!c.straddled.empty()) cj["straddled_inequalities"] = c.straddled;
  if (c.status == verify::ClusterStatus::infeasible && !c.root.empty()) cj["root"] = box_json(c.root);
  if (c.status != verify::ClusterStatus::curve) {
    cj["certificate"] = certificate_json(c.certificate);
    if (!c.subsystem.empty()) cj["subsystem"] = c.subsystem;
    if (!c.argument.empty()) cj["argument"] = c.argument;
    if (c.excluding_equation >= 0) cj["excluding_equation"] = c.excluding_equation;
    if (!c.exact_root.empty()) cj["exact_root"] = c.exact_root;
  }
  if (c.status == verify::ClusterStatus::curve) {
    json xs = json::array();
    for (auto& x : c.crossings) {
      json xj = certificate_json(x.certificate);
      xj["member"] = x.box;
      xj["chart"] = x.chart;
      xj["dropped_equations"] = x.dropped_equations;
      xs.push_back(xj);
    }
    cj["crossings"] = xs;
    cj["crossings_certified"] = c.crossings_certified;
    cj["crossings_fraction"] = c.crossings.empty() ? 0.0 : double(c.crossings_certified) / c.crossings.size();
    if (c.map) cj["map"] = verify::map_json(*c.map);
  }
  return cj;
}

}  // namespace

void add_verification(json& j, const formulate::Formulation& f, const verify::VerifyReport& r) {
  j["certified_roots"] = r.certified_roots;
  j["headline"] = r.headline;
  j["verification"] = {{"certified_roots", r.certified_roots}, {"unverified", r.unverified}, {"curves", r.curves}, {"empty", r.empty},
                       {"exact", r.exact}, {"seconds", r.seconds}};
  if (r.timed_out) j["verification"]["timed_out"] = true;
  if (r.curves) {
    // The curve clusters' maps, summed: components, and whether every one is proved.
    j["verification"]["map"] = {{"closed_curves", r.closed_curves},
                                {"open_arcs", r.open_arcs},
                                {"branches", r.branches},
                                {"singular_points", r.singular_points},
                                {"proved", r.maps_proved}};
  }
  if (!r.interval_constants.empty()) j["verification"]["interval_constants"] = r.interval_constants;
  if (r.inequalities) {
    j["verification"]["inequalities"] = r.inequalities;
    j["verification"]["infeasible"] = r.infeasible;
  }
  json roots = json::array();  // one per distinct certified root, in the output variables
  for (size_t k = 0; k < r.clusters.size(); ++k) {
    const auto& c = r.clusters[k];
    if (c.status != verify::ClusterStatus::certified || c.duplicate_of >= 0) continue;
    json mid = json::array();
    for (auto& x : c.root) mid.push_back(median(x));
    roots.push_back({{"cluster", k}, {"midpoint", mid}, {"box", box_json(c.root)}});
  }
  j["roots"] = roots;
  json clusters = json::array();
  for (auto& c : r.clusters) clusters.push_back(cluster_json(f, c));
  j["clusters"] = clusters;
}

}  // namespace linkbox::report
