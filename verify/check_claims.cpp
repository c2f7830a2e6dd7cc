#include "verify/check_claims.hpp"

#include "verify/cluster.hpp"
#include "verify/headline.hpp"

#include <nlohmann/json.hpp>

namespace linkbox::verify {

using nlohmann::json;

namespace {

// Certified roots that overlap without a proof that they are one (merge_duplicates' count):
// in each group of touching root boxes, every member but one that is not a proved duplicate.
int overlaps_unresolved(const formulate::Formulation& f, const VerifyReport& r) {
  std::vector<Box> roots;
  std::vector<const ClusterReport*> of;
  for (auto& c : r.clusters)
    if (c.status == ClusterStatus::certified && !c.root.empty()) {
      roots.push_back(c.root);
      of.push_back(&c);
    }
  int unresolved = 0;
  const std::vector<bool> periodic(f.output_names().size(), f.outputs_are_angles());
  for (auto& g : cluster_boxes(roots, periodic)) {
    int duplicates = 0;
    for (int i : g) duplicates += of[i]->duplicate_of >= 0;
    unresolved += static_cast<int>(g.size()) - 1 - duplicates;
  }
  return unresolved;
}

// The search's completeness as the result states it must at least be consistent: a complete
// search left no pending box in any sub-problem and gives no stop reason.
void check_completeness_stated(const json& j, std::vector<std::string>& failures) {
  const bool complete = j.at("complete").get<bool>();
  bool pending = j.value("pending_boxes", 0L) != 0 || j.value("volume_left", 0.0) != 0;
  for (auto& s : j.value("subproblem_stats", json::array()))
    pending = pending || !s.value("complete", true) || !s.value("pending", json::array()).empty();
  if (complete && (pending || j.contains("stop_reason")))
    failures.push_back("complete is claimed, but pending boxes, unexplored volume or a stop reason are listed");
  if (!complete && !j.contains("stop_reason")) failures.push_back("an incomplete search gives no stop_reason");
}

template <class T>
void same(const json& j, const char* key, const T& recomputed, const std::string& what, std::vector<std::string>& failures) {
  if (!j.contains(key) || j.at(key).get<T>() != recomputed)
    failures.push_back(what + " says " + (j.contains(key) ? j.at(key).dump() : "nothing") + ", but its certificates give " +
                       json(recomputed).dump());
}

void check_counts(const json& j, const VerifyReport& r, std::vector<std::string>& failures) {
  same(j, "headline", r.headline, "the headline", failures);
  same(j, "certified_roots", r.certified_roots, "certified_roots", failures);
  const json& v = j.at("verification");
  same(v, "certified_roots", r.certified_roots, "verification.certified_roots", failures);
  same(v, "unverified", r.unverified, "verification.unverified", failures);
  same(v, "curves", r.curves, "verification.curves", failures);
  same(v, "empty", r.empty, "verification.empty", failures);
  same(v, "exact", r.exact, "verification.exact", failures);
  if (r.inequalities || v.contains("inequalities")) {
    same(v, "inequalities", r.inequalities, "verification.inequalities", failures);
    same(v, "infeasible", r.infeasible, "verification.infeasible", failures);
  }
  if (r.curves || v.contains("map")) {
    const json& m = v.contains("map") ? v.at("map") : json::object();
    same(m, "closed_curves", r.closed_curves, "verification.map.closed_curves", failures);
    same(m, "open_arcs", r.open_arcs, "verification.map.open_arcs", failures);
    if (r.branches || r.singular_points || m.contains("branches")) {
      same(m, "branches", r.branches, "verification.map.branches", failures);
      same(m, "singular_points", r.singular_points, "verification.map.singular_points", failures);
    }
    same(m, "proved", r.maps_proved, "verification.map.proved", failures);
  }
}

// `roots`: one entry per distinct certified root, its cluster's root box and a midpoint in it.
void check_roots(const json& j, const VerifyReport& r, std::vector<std::string>& failures) {
  json expected = json::array();
  for (size_t k = 0; k < r.clusters.size(); ++k) {
    const auto& c = r.clusters[k];
    if (c.status != ClusterStatus::certified || c.duplicate_of >= 0) continue;
    json box = json::array();
    for (auto& x : c.root) box.push_back({x.lower(), x.upper()});
    expected.push_back({{"cluster", k}, {"box", box}});
  }
  const json& roots = j.contains("roots") ? j.at("roots") : json::array();
  bool fits = roots.size() == expected.size();
  for (size_t k = 0; fits && k < roots.size(); ++k) {
    fits = roots[k].at("cluster") == expected[k].at("cluster") && roots[k].at("box") == expected[k].at("box");
    const json& mid = roots[k].at("midpoint");
    fits = fits && mid.size() == expected[k].at("box").size();
    for (size_t i = 0; fits && i < mid.size(); ++i)
      fits = expected[k]["box"][i][0].get<double>() <= mid[i].get<double>() &&
             mid[i].get<double>() <= expected[k]["box"][i][1].get<double>();
  }
  if (!fits) failures.push_back("roots does not list each distinct certified root's box, with a midpoint inside it");
}

}  // namespace

const std::vector<TrustedField>& trusted_fields() {
  static const std::vector<TrustedField> fields = {
      {"complete", "that the search was complete needs a log of the search (only its consistency is checked)"},
      {"stop_reason", "the search's own account"},
      {"refinement_stopped", "the search's own account"},
      {"pending_boxes", "the search's own account"},
      {"volume_left", "the search's own account"},
      {"parameters", "the settings the search ran with (arith included: a float search proves no exclusion)"},
      {"strategy", "the settings the search ran with"},
      {"bisect", "the settings the search ran with"},
      {"race", "figures of the search"},
      {"race_choices", "the search's own account of its race"},
      {"stats", "figures of the search"},
      {"contractors", "figures of the search"},
      {"subproblem_stats", "figures of the search (pending boxes: consistency only)"},
      {"model", "figures of the formulation"},
      {"model_notes", "figures of the formulation"},
      {"case", "a name"},
      {"kind", "a name"},
      {"case_file", "a hint: the case is named by --case or found there, and bound by case_sha256"},
      {"checkpoint", "where the search's state was kept, to go on with"},
      {"format", "read to parse the result"},
      {"linkbox", "the version that wrote the result"},
      {"verification.seconds", "a figure of the run"},
      {"verification.timed_out", "the run's own account (its skipped clusters are unverified either way)"},
  };
  return fields;
}

void check_claims(const json& j, const formulate::Formulation& f, std::vector<ClusterReport> clusters,
                  std::vector<std::string>& failures) {
  VerifyReport r;
  r.clusters = std::move(clusters);
  r.inequalities = static_cast<int>(f.natural(0).inequalities.size());
  r.interval_constants = f.natural(0).interval_constants;
  r.assumed_bounds = f.natural(0).assumed_bounds;
  solve::CaseResult search;
  search.complete = j.at("complete").get<bool>();
  search.stop_reason = j.value("stop_reason", "");
  if (j.contains("refinement_stopped")) {
    search.refine_stop = j.at("refinement_stopped").at("reason").get<std::string>();
    search.unrefined = j.at("refinement_stopped").at("boxes").get<long>();
  }
  search.rigorous = j.at("parameters").at("arith") == "verified";
  summarise(r, overlaps_unresolved(f, r), search);
  check_counts(j, r, failures);
  check_roots(j, r, failures);
  check_completeness_stated(j, failures);
  const std::string unit = f.outputs_are_angles() ? "radians" : "";
  if (j.value("variables_unit", unit) != unit) failures.push_back("variables_unit is not the case's");
}

}  // namespace linkbox::verify
