#include "report/text.hpp"

#include <algorithm>

namespace linkbox::report {

namespace {
std::string volume_text(double share) {
  char t[32];
  std::snprintf(t, sizeof t, "%.3g%%", 100 * share);
  return t;
}
}  // namespace

void print_summary(std::FILE* out, const formulate::LoadedCase& c, const solve::RunOptions& o,
                   const solve::CaseResult& r, bool json_written) {
  const auto& f = *c.formulation;
  std::fprintf(out, "case      %s (%s, %s)\n", c.name.c_str(), c.kind.c_str(), c.file.c_str());
  const std::string asked = o.strategy.prune.text(), ran = r.strategy.text();
  std::string race_line;
  std::string prune = asked == ran || ran.empty() ? asked : asked + " (ran " + ran + ")";
  if (!r.subproblems.empty() && r.subproblems[0].race.size() > 1) {
    // Work in boxes of propagation (solve/search.hpp), the winner last.
    std::string race;
    for (auto& [name, work] : r.subproblems[0].race) {
      char w[64];
      std::snprintf(w, sizeof w, " %s %.3g,", name.c_str(), work);
      race += w;
    }
    race.pop_back();
    race_line = "race      work (in boxes of propagation):" + race + "\n";
  }
  const std::string asked_bisect = solve::to_string(o.bisect);
  const std::string bisect =
      asked_bisect == r.bisect || r.bisect.empty() ? asked_bisect : asked_bisect + " (" + r.bisect + ")";
  char rho[48];
  if (o.params.rho > 0 || r.rho <= 0)
    std::snprintf(rho, sizeof rho, "%g", o.params.rho);
  else
    std::snprintf(rho, sizeof rho, "auto (%g)", r.rho);
  std::fprintf(out, "strategy  prune=%s bisect=%s sigma=%g rho=%s order=%s threads=%d%s\n", prune.c_str(), bisect.c_str(),
               o.params.sigma, rho,
               o.params.order == solve::Order::depth_first ? "dfs" : "bfs", o.threads,
               r.rigorous ? "" : "  arith=float (UNVERIFIED: boxes discarded on float evidence)");
  std::fputs(race_line.c_str(), out);
  // Where the settings came from, when not all are defaults: "sigma (case file), rho (flag)".
  std::string sources;
  for (auto& [name, from] : o.setting_source) sources += (sources.empty() ? "" : ", ") + name + " (" + from + ")";
  if (!sources.empty()) std::fprintf(out, "settings  %s; the rest default\n", sources.c_str());
  if (f.subproblem_count() == 1)
    if (auto sub = f.subproblem(0); sub.lph)
      std::fprintf(out, "model     %zu primary + %zu dummy variables; %zu linear, %zu parabolic, %zu hyperbolic equations\n",
                   sub.lph->primary.size(), sub.lph->variables.size() - sub.lph->primary.size(), sub.lph->linear.size(),
                   sub.lph->parabolic.size(), sub.lph->hyperbolic.size());
  // A lifted system of a thousand functions has as many notes: the first few, then a count.
  const std::vector<std::string> notes = f.model_notes();
  constexpr size_t kNotes = 12;
  for (size_t k = 0; k < notes.size() && k < kNotes; ++k) std::fprintf(out, "model     %s\n", notes[k].c_str());
  if (notes.size() > kNotes)
    std::fprintf(out, "model     ... and %zu more notes (all in the JSON's model_notes)\n", notes.size() - kNotes);
  std::fprintf(out, "\n%-12s %10s %10s %10s %10s %10s %10s\n", "subproblems", "processed", "empty", "split", "solution",
               "search [s]", "wall [s]");
  std::fprintf(out, "%-12zu %10ld %10ld %10ld %10ld %10.3f %10.3f\n", r.subproblems.size(), r.total.processed,
               r.total.empty, r.total.split, r.total.solution, r.total.seconds, r.seconds);
  if (r.boxes_taken != r.total.processed)
    std::fprintf(out, "(the progress lines' count: %ld boxes taken by this run, raced candidates included; "
                      "the table counts each sub-problem's result)\n", r.boxes_taken);
  std::fprintf(out, "\n%s\n",
               r.complete ? "complete: every box of the domain was processed"
                          : ("INCOMPLETE (" + r.stop_reason + "): results cover only what was explored; " +
                             std::to_string(r.pending_boxes) + " boxes pending, " + volume_text(r.volume_left) +
                             " of the domain's volume left")
                                .c_str());
  if (r.unrefined)
    std::fprintf(out, "refinement stopped (%s): %ld solution %s left unrefined\n", r.refine_stop.c_str(),
                 r.unrefined, r.unrefined == 1 ? "box" : "boxes");
  const auto names = f.output_names();
  size_t total = 0;
  for (auto& s : r.subproblems) total += s.solutions.size();
  if (total) std::fprintf(out, "\nsolution boxes (%s, midpoints):\n", f.outputs_are_angles() ? "radians" : "values");
  constexpr size_t kShown = 20;
  size_t shown = 0;
  for (auto& s : r.subproblems)
    for (auto& b : s.solutions) {
      if (shown++ == kShown) {
        std::fprintf(out, "  ... %zu more %s\n", total - kShown,
                     json_written ? "in the JSON output" : "(--json OUT writes them all)");
        return;
      }
      const Box box = f.to_output(s.index, b);
      std::fprintf(out, "  [%s]", s.label.c_str());
      for (size_t i = 0; i < box.size(); ++i) std::fprintf(out, " %s=%+.6f", names[i].c_str(), median(box[i]));
      std::fprintf(out, "  (width %.1e)\n", max_width(box));
    }
}

namespace {

// A curve cluster's map: what it is, then each component's extent per output variable.
void print_map(std::FILE* out, const std::vector<std::string>& names, const verify::ClusterReport& cl) {
  std::fprintf(out, "  curve cluster of %zu boxes: %s\n", cl.boxes.size(), cl.map->statement.c_str());
  for (auto& comp : cl.map->components) {
    const char* what = !cl.map->proved      ? "arcs joined"
                       : comp.singular_ends ? "branch"
                       : comp.closed        ? "closed curve"
                                            : "open arc";
    std::fprintf(out, "    %s (%zu arcs):", what, comp.arcs.size());
    for (size_t i = 0; i < comp.extent.size() && i < names.size(); ++i)
      std::fprintf(out, " %s in [%+.4f, %+.4f]", names[i].c_str(), comp.extent[i].lower(), comp.extent[i].upper());
    std::fprintf(out, "\n");
  }
  for (auto& p : cl.map->singular_points) {
    std::string at;
    for (auto& x : p.point) at += (at.empty() ? "" : ", ") + x;
    std::fprintf(out, "    singular point (%s) at (%s) in the natural unknowns: the only one in its box of width %.1e; %d branches reach it\n",
                 verify::to_string(p.kind), at.c_str(), max_width(p.where()), p.branches);
  }
  for (auto& r : cl.map->singular_regions) {
    std::fprintf(out, "    possible singular point:");
    for (size_t i = 0; i < r.size() && i < names.size(); ++i)
      std::fprintf(out, " %s in [%+.4f, %+.4f]", names[i].c_str(), r[i].lower(), r[i].upper());
    std::fprintf(out, "\n");
  }
}

// A curve cluster without a map: what its crossings show, and that it is not a proof.
void print_crossings(std::FILE* out, const verify::ClusterReport& cl) {
  size_t dropped = 0;
  for (auto& x : cl.crossings) dropped = std::max(dropped, x.dropped_equations.size());
  std::fprintf(out, "  curve, not proved: %zu boxes, %d/%zu crossings certified", cl.boxes.size(), cl.crossings_certified,
               cl.crossings.size());
  if (dropped)
    std::fprintf(out, " (a root of all equations but %zu on a face; %s contains 0 there)\n", dropped,
                 dropped == 1 ? "the other" : "the others");
  else
    std::fprintf(out, " (a root on a face of each)\n");
}

}  // namespace

void print_verification(std::FILE* out, const formulate::LoadedCase& c, const verify::VerifyReport& v) {
  const auto names = c.formulation->output_names();
  std::fprintf(out, "\nverification (%.3f s): %s\n", v.seconds, v.headline.c_str());
  int k = 0;
  for (auto& cl : v.clusters) {
    if (cl.status != verify::ClusterStatus::certified || cl.duplicate_of >= 0) continue;
    std::fprintf(out, "  root %2d:", ++k);
    for (size_t i = 0; i < cl.root.size(); ++i) std::fprintf(out, " %s=%+.12f", names[i].c_str(), median(cl.root[i]));
    std::fprintf(out, "  (certified box width %.1e)\n", max_width(cl.root));
  }
  for (auto& cl : v.clusters) {
    if (cl.status == verify::ClusterStatus::curve && cl.map)
      print_map(out, names, cl);
    else if (cl.status == verify::ClusterStatus::curve)
      print_crossings(out, cl);
    else if (cl.status == verify::ClusterStatus::unverified)
      std::fprintf(out, "  unverified cluster of %zu boxes: %s\n", cl.boxes.size(), cl.reason.c_str());
    else if (cl.status == verify::ClusterStatus::infeasible)
      std::fprintf(out, "  excluded cluster of %zu boxes: %s\n", cl.boxes.size(), cl.reason.c_str());
  }
}

}  // namespace linkbox::report
