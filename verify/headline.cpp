#include "verify/headline.hpp"

#include <map>
#include <vector>

namespace linkbox::verify {

namespace {

// Reasons are counted in the headline without their trailing detail in parentheses.
std::string without_detail(const std::string& reason) {
  const size_t open = reason.rfind(" (");
  return !reason.empty() && reason.back() == ')' && open != std::string::npos ? reason.substr(0, open) : reason;
}

std::string count(int k, const char* one, const char* many) { return std::to_string(k) + " " + (k == 1 ? one : many); }

// "2 isolated roots, 1 closed curve and 2 open arcs"; isolated < 0 leaves them out.
std::string map_words(int isolated, const VerifyReport& r) {
  std::vector<std::string> parts;
  if (isolated >= 0) parts.push_back(count(isolated, "isolated root", "isolated roots"));
  if (r.closed_curves) parts.push_back(count(r.closed_curves, "closed curve", "closed curves"));
  if (r.open_arcs) parts.push_back(count(r.open_arcs, "open arc", "open arcs") + " (ending on the domain's boundary)");
  if (r.branches) parts.push_back(count(r.branches, "branch", "branches"));
  if (r.singular_points) parts.push_back(count(r.singular_points, "singular point", "singular points"));
  std::string s;
  for (size_t k = 0; k < parts.size(); ++k) s += (k == 0 ? "" : k + 1 == parts.size() ? " and " : ", ") + parts[k];
  return s;
}

}  // namespace

void summarise(VerifyReport& report, int overlaps_unresolved, const solve::CaseResult& result) {
  bool all_unique = true;
  bool maps_proved = true;
  std::map<std::string, int> reasons;
  for (auto& c : report.clusters) {
    if (c.status == ClusterStatus::certified) {
      // A duplicate is proved to hold the same root as another cluster, not to hold only that
      // one: its hull may hold a second root (two close pairs), so it must be unique too.
      all_unique = all_unique && c.certificate.unique_in_hull;
      if (!c.certificate.unique_in_hull) reasons[without_detail(c.reason)]++;
      if (c.duplicate_of < 0) report.certified_roots++;
    } else if (c.status == ClusterStatus::curve) {
      report.curves++;
      maps_proved = maps_proved && c.map && c.map->proved;
      if (c.map && c.map->proved) {
        for (auto& comp : c.map->components)
          ++(comp.singular_ends ? report.branches : comp.closed ? report.closed_curves : report.open_arcs);
        report.singular_points += static_cast<int>(c.map->singular_points.size());
      }
    } else if (c.status == ClusterStatus::empty) {
      report.empty++;
    } else if (c.status == ClusterStatus::infeasible) {
      report.infeasible++;
    } else if (c.status == ClusterStatus::unverified) {
      report.unverified++;
      reasons[without_detail(c.reason)]++;
    }
  }
  report.maps_proved = report.curves > 0 && maps_proved;
  report.exact = result.complete && result.rigorous && report.unverified == 0 && (report.curves == 0 || maps_proved) &&
                 all_unique && overlaps_unresolved == 0;
  const int n = report.certified_roots;
  std::string bounds;
  for (auto& b : report.assumed_bounds) bounds += (bounds.empty() ? "" : ", ") + b;
  const std::string domain = bounds.empty() ? "in the domain" : "in the domain (with " + bounds + ", a default bound)";
  const std::string where =
      report.inequalities == 0 ? domain
                               : domain + " where the " +
                                     (report.inequalities == 1 ? "inequality holds" : "inequalities hold");
  const std::string excluded =
      report.infeasible ? ", " + std::to_string(report.infeasible) + " proved to violate an inequality" : "";
  // Interval coefficients stand for every value in them: each proof holds for all of them.
  const std::string family =
      report.interval_constants.empty() ? "" : " for every value of the interval constants";
  if (report.exact && report.curves) {
    const std::string singular =
        report.singular_points
            ? ", singular points by exact arithmetic, each the only one in its box; inside those boxes the branches are "
              "not followed"
            : "";
    report.headline = "exactly " + map_words(n, report) + " " + where + family +
                      ", each certified (isolated roots by interval Newton, curves by arc certificates" + singular + ")" +
                      excluded;
    return;
  }
  if (report.exact) {
    report.headline = "exactly " + std::to_string(n) + " root" + (n == 1 ? "" : "s") + " " + where + family +
                      ", each in its certified box" + (report.infeasible ? " (" + excluded.substr(2) + ")" : "");
    return;
  }
  report.headline = std::to_string(n) + " certified" + family;
  if (report.curves) report.headline += ", " + std::to_string(report.curves) + " curve cluster(s)";
  if (report.closed_curves + report.open_arcs + report.branches)
    report.headline += " (" + map_words(-1, report) + " proved)";
  if (report.unverified) report.headline += ", " + std::to_string(report.unverified) + " unresolved";
  if (report.empty) report.headline += ", " + std::to_string(report.empty) + " proved empty";
  report.headline += excluded;
  if (overlaps_unresolved) report.headline += ", " + std::to_string(overlaps_unresolved) + " overlapping roots unresolved";
  if (!result.complete) report.headline += "; search incomplete (" + result.stop_reason + ")";
  if (result.complete && result.unrefined)
    report.headline += "; refinement stopped (" + result.refine_stop + "): " + count(static_cast<int>(result.unrefined),
                       "solution box", "solution boxes") + " left unrefined";
  if (!result.rigorous)
    report.headline = "UNVERIFIED search (--arith float: boxes were discarded on float evidence, roots may be missing): " +
                      report.headline;
  std::string why;
  // "inflation failed: 1 cluster", never "inflation failed x1", which reads as a variable.
  for (auto& [r, k] : reasons)
    why += (why.empty() ? "" : "; ") + r + ": " + std::to_string(k) + (k == 1 ? " cluster" : " clusters");
  if (!why.empty()) report.headline += " (" + why + ")";
}

}  // namespace linkbox::verify
