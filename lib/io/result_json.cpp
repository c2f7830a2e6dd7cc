#include "io/result_json.hpp"

#include <nlohmann/json.hpp>

namespace linkbox::io {

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
          {"solution_boxes", s.solution}, {"shrinks", s.shrinks}, {"seconds", s.seconds}};
}
}  // namespace

json result_json(const std::string& case_name, const std::string& case_file,
                 const formulate::Formulation& formulation, const solve::RunOptions& options,
                 const solve::CaseResult& result) {
  const auto& p = options.params;
  json j;
  j["case"] = case_name;
  j["case_file"] = case_file;
  j["kind"] = formulation.kind();
  j["variables"] = formulation.output_names();
  j["variables_unit"] = formulation.outputs_are_angles() ? "radians" : "";
  std::string prune;
  for (auto& c : options.strategy.contractors) prune += (prune.empty() ? "" : ",") + c;
  j["parameters"] = {{"sigma", p.sigma},
                     {"rho", p.rho},
                     {"order", p.order == solve::Order::depth_first ? "dfs" : "bfs"},
                     {"prune", prune},
                     {"lp", options.strategy.lp},
                     {"arith", options.strategy.rigorous ? "verified" : "float (UNVERIFIED)"},
                     {"time_limit", p.time_limit},
                     {"max_boxes", p.max_boxes},
                     {"threads", options.threads}};
  // Model size of an L/P/H formulation (iterated-LP paper): primary, dummy, #L, #P, #H.
  if (formulation.subproblem_count() == 1) {
    const auto sub = formulation.subproblem(0);
    if (sub.lph) {
      const auto& m = *sub.lph;
      j["model"] = {{"primary", m.primary.size()}, {"dummy", m.variables.size() - m.primary.size()},
                    {"linear", m.linear.size()}, {"parabolic", m.parabolic.size()}, {"hyperbolic", m.hyperbolic.size()}};
    }
  }
  j["complete"] = result.complete;
  if (!result.complete) j["stop_reason"] = result.stop_reason;
  json stats = stats_json(result.total);
  stats["subproblems"] = result.subproblems.size();
  stats["seconds"] = result.seconds;
  stats["cpu_seconds"] = result.total.seconds;
  j["stats"] = stats;
  json contractors = json::array();
  for (size_t k = 0; k < result.counters.size(); ++k) {
    auto& c = result.counters[k];
    contractors.push_back({{"name", result.contractor_names.at(k)}, {"calls", c.calls}, {"emptied", c.emptied},
                           {"volume_removed", c.volume_removed}, {"seconds", c.seconds},
                           {"lps_solved", c.lps_solved}, {"lp_iterations", c.lp_iterations}});
  }
  j["contractors"] = contractors;
  json subs = json::array(), sols = json::array();
  for (auto& s : result.subproblems) {
    // The sub-problem's equations, for the residual of its solution boxes.
    const auto equations = s.solutions.empty() ? std::vector<model::Polynomial>{}
                                               : formulation.subproblem(s.index).system.equations;
    json sj = stats_json(s.stats);
    sj["index"] = s.index;
    sj["label"] = s.label;
    sj["equations"] = s.equations;
    sj["variables"] = s.variables;
    sj["complete"] = s.complete;
    subs.push_back(sj);
    for (auto& box : s.solutions) {
      json sol = {{"subproblem", s.index},
                  {"box", box_json(formulation.to_output(s.index, box))},
                  {"search_box", box_json(box)},
                  {"residual", model::residual_bound(equations, box)}};
      for (auto& m : formulation.declared_outputs(s.index, box)) {
        json rows = json::array();
        for (auto& row : m.rows) rows.push_back(box_json(row));
        sol[m.name] = rows;  // e.g. "rotation": 3x3 [lo, hi], row-major
      }
      sols.push_back(sol);
    }
  }
  j["subproblem_stats"] = subs;
  j["solutions"] = sols;
  return j;
}

}  // namespace linkbox::io
