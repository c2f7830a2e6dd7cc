#include "verify/certify_case.hpp"

#include "verify/check_proofs.hpp"

#include "verify/cluster.hpp"
#include "verify/symmetric_map.hpp"
#include "verify/curve.hpp"
#include "verify/curve_map.hpp"
#include "verify/headline.hpp"
#include "verify/isolated.hpp"

#include "interval/rigorous.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>

namespace linkbox::verify {

const char* to_string(ClusterStatus s) {
  switch (s) {
    case ClusterStatus::certified: return "certified";
    case ClusterStatus::unverified: return "unverified";
    case ClusterStatus::curve: return "curve";
    case ClusterStatus::empty: return "empty";
    case ClusterStatus::infeasible: return "infeasible";
  }
  return "?";
}

namespace {

// Two clusters whose certified roots overlap are the same root when one certificate covers
// both boxes (the later one is marked duplicate_of the first); otherwise both stay, and the
// run is not exact. Returns the number of overlaps left unresolved.
int merge_duplicates(const formulate::Formulation& f, VerifyReport& report,
                     const std::vector<bool>& periodic, const newton::NewtonOptions& options) {
  std::vector<Box> roots;       // certified root boxes (output variables)
  std::vector<size_t> root_of;  // cluster index of each
  for (size_t i = 0; i < report.clusters.size(); ++i)
    if (report.clusters[i].status == ClusterStatus::certified) {
      roots.push_back(report.clusters[i].root);
      root_of.push_back(i);
    }
  int unresolved = 0;
  for (auto& g : cluster_boxes(roots, periodic)) {
    if (g.size() < 2) continue;
    ClusterReport& first = report.clusters[root_of[g[0]]];
    for (size_t k = 1; k < g.size(); ++k) {
      ClusterReport& other = report.clusters[root_of[g[k]]];
      const auto& sys = f.natural(first.chart);
      Box joint = first.certificate.box;
      try {
        joint = hull(joint, f.output_to_natural(first.chart, unwrap(other.root, first.root, f.outputs_are_angles())));
      } catch (const std::exception&) {
      }
      newton::Certificate both = certify_natural(sys, joint, options);
      if (both.status == newton::Status::certified && both.unique_in_hull) {
        other.duplicate_of = static_cast<int>(root_of[g[0]]);
        other.reason = "same root as another cluster (found by two sub-problems)";
      } else {
        ++unresolved;
      }
    }
  }
  return unresolved;
}

// Calls work(k) for k < n on `threads` threads (this one included), each taking the next k;
// the first exception (by k) is rethrown once all are done, as one thread would have thrown it.
template <class Work>
void for_each_index(size_t n, int threads, const Work& work) {
  std::atomic<size_t> next{0};
  std::vector<std::exception_ptr> errors(n);
  auto run = [&] {
    for (size_t k; (k = next.fetch_add(1)) < n;) {
      try {
        work(k);
      } catch (...) {
        errors[k] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::min<int>(threads, static_cast<int>(n)); ++t)
    pool.emplace_back([&] {
      run();
      rigorous::release_thread_caches();
    });
  run();
  for (auto& t : pool) t.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

// Attaches the certified map of a cluster that looks like a curve; the map, when there is
// one, says what the cluster is, whichever way the crossings went.
void map_curve(const formulate::Formulation& f, const std::vector<Box>& member, bool chart_holds_cluster,
               ClusterReport& c, const newton::NewtonOptions& options) {
  std::vector<std::uint64_t> charts(member.size(), c.chart);
  if (!chart_holds_cluster)
    for (size_t k = 0; k < member.size(); ++k) charts[k] = f.chart_for(member[k]);
  c.map = map_cluster(f, member, charts, options);
  if (!c.map) return;
  c.status = ClusterStatus::curve;
  c.reason = c.map->statement;
}

// The map of a cluster of a symmetric six-joint loop (its closure is redundant along curves,
// so no square subsystem maps it), when one can be stated.
std::optional<CurveMap> symmetric_map_of(const formulate::Formulation& f, const std::vector<Box>& member) {
  const auto loop = SymmetricLoop::of(f);
  if (!loop) return std::nullopt;
  for (const Box& m : member)
    if (max_width(m) > kSymmetricMember) return std::nullopt;
  return map_symmetric(*loop, member);
}

void state_symmetric_map(CurveMap map, ClusterReport& c) {
  if (map.arcs.empty()) {
    c.status = ClusterStatus::empty;
    c.reason = "proved to hold no root: every piece excluded through the loop's symmetry";
    return;
  }
  c.map = std::move(map);
  c.status = ClusterStatus::curve;
  c.reason = c.map->statement;
}

// Proved maps of two clusters whose arcs may meet could count one curve twice: both are
// then stated as not proved.
void separate_maps(const formulate::Formulation& f, VerifyReport& report) {
  auto& cs = report.clusters;
  for (size_t i = 0; i < cs.size(); ++i)
    for (size_t k = i + 1; k < cs.size(); ++k) {
      if (!cs[i].map || !cs[k].map || !cs[i].map->proved || !cs[k].map->proved) continue;
      if (maps_apart(f, *cs[i].map, *cs[k].map)) continue;
      for (size_t c : {i, k}) {
        cs[c].map->proved = false;
        cs[c].map->statement += "; not proved: its arcs may meet another cluster's";
        cs[c].reason = cs[c].map->statement;
      }
    }
}

}  // namespace

std::vector<ClusterTask> cluster_tasks(const formulate::Formulation& f, const solve::CaseResult& result,
                                       int threads) {
  std::vector<std::pair<size_t, size_t>> where;
  std::vector<const solve::SubResult*> sub;
  std::vector<double> residual;
  for (auto& s : result.subproblems)
    for (size_t k = 0; k < s.solutions.size(); ++k) {
      where.emplace_back(s.index, k);
      sub.push_back(&s);
      residual.push_back(s.residuals.at(k));
    }
  // Angles come out of a rigorous atan2 (MPFI): a third of bicyclohexane's verification, so
  // on every thread.
  std::vector<Box> outputs(where.size());
  for_each_index(where.size(), threads,
                 [&](size_t i) { outputs[i] = f.to_output(where[i].first, sub[i]->solutions[where[i].second]); });
  std::vector<Box> uncertified;
  std::vector<int> uncertified_index;
  std::vector<std::vector<int>> groups;
  for (int i = 0; i < static_cast<int>(where.size()); ++i) {
    const size_t k = where[i].second;
    // A box certified during the search holds exactly one root: a cluster of its own.
    if (k < sub[i]->certified.size() && sub[i]->certified[k]) {
      groups.push_back({i});
    } else {
      uncertified.push_back(outputs[i]);
      uncertified_index.push_back(i);
    }
  }
  const std::vector<bool> periodic(f.output_names().size(), f.outputs_are_angles());
  for (auto& g : cluster_boxes(uncertified, periodic)) {
    for (int& i : g) i = uncertified_index[i];
    groups.push_back(std::move(g));
  }
  std::sort(groups.begin(), groups.end());  // by smallest member: independent of which were certified
  std::vector<ClusterTask> tasks(groups.size());
  for (size_t k = 0; k < groups.size(); ++k)
    for (int i : groups[k]) {
      tasks[k].boxes.push_back(where[i]);
      tasks[k].outputs.push_back(outputs[i]);
      tasks[k].residuals.push_back(residual[i]);
    }
  return tasks;
}

namespace {

// The cluster's boxes, worst residual and hull; its members (output variables, unwrapped).
ClusterReport gather(const formulate::Formulation& f, const ClusterTask& task, std::vector<Box>& member) {
  const bool angles = f.outputs_are_angles();
  ClusterReport c;
  for (size_t i = 0; i < task.outputs.size(); ++i) {
    c.boxes.push_back(task.boxes.at(i));
    member.push_back(unwrap(task.outputs[i], task.outputs[0], angles));
    c.max_residual = std::max(c.max_residual, task.residuals.at(i));
  }
  c.hull = member.at(0);
  for (auto& b : member) c.hull = hull(c.hull, b);
  return c;
}

}  // namespace

ClusterReport skipped_cluster(const formulate::Formulation& f, const ClusterTask& task, const std::string& why) {
  std::vector<Box> member;
  ClusterReport c = gather(f, task, member);
  c.reason = "verification skipped (" + why + ")";
  return c;
}

ClusterReport verify_cluster(const formulate::Formulation& f, const ClusterTask& task, const VerifyOptions& options) {
  const std::vector<bool> periodic(f.output_names().size(), f.outputs_are_angles());
  if (options.skip_rest && options.skip_rest()) return skipped_cluster(f, task, "interrupted");
  std::vector<Box> member;
  ClusterReport c = gather(f, task, member);
  c.chart = f.chart_for(c.hull);
  Box start;
  try {
    start = f.output_to_natural(c.chart, c.hull);
  } catch (const std::exception& e) {
    c.reason = std::string("cluster too wide for a chart: ") + e.what();
  }
  if (!start.empty()) certify_isolated(f, f.natural(c.chart), start, member, periodic, c, options.newton);
  if (!start.empty()) certify_coupled(f, start, member, periodic, c);
  std::optional<CurveMap> symmetric;
  if (c.status != ClusterStatus::certified) symmetric = symmetric_map_of(f, member);
  // A proved symmetric map states more than crossings of n - 1 equations could.
  if (!symmetric || !(symmetric->proved || symmetric->arcs.empty())) {
    const bool curve_like = classify_curve(f, member, !start.empty(), c, options.newton);
    if (curve_like) map_curve(f, member, !start.empty(), c, options.newton);
  }
  if (symmetric && !c.map && c.status != ClusterStatus::certified) state_symmetric_map(std::move(*symmetric), c);
  if (!start.empty()) classify_inequalities(f.natural(c.chart), start, c);
  return c;
}

VerifyReport conclude(const formulate::Formulation& f, std::vector<ClusterReport> clusters,
                      const solve::CaseResult& result, const VerifyOptions& options) {
  VerifyReport report;
  report.clusters = std::move(clusters);
  const std::vector<bool> periodic(f.output_names().size(), f.outputs_are_angles());
  const int overlaps_unresolved = merge_duplicates(f, report, periodic, options.newton);
  report.inequalities = static_cast<int>(f.natural(0).inequalities.size());
  report.interval_constants = f.natural(0).interval_constants;
  report.assumed_bounds = f.natural(0).assumed_bounds;
  separate_maps(f, report);
  summarise(report, overlaps_unresolved, result);
  return report;
}

VerifyReport verify_case(const formulate::Formulation& f, const solve::CaseResult& result,
                         const VerifyOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<ClusterTask> tasks = cluster_tasks(f, result, options.threads);
  // Clusters are independent: with threads, each takes the next one, and the reports keep
  // the clusters' order.
  std::vector<ClusterReport> clusters(tasks.size());
  std::atomic<size_t> done{0};
  std::mutex line_m;
  auto last_line = t0;
  std::atomic<bool> timed_out{false};
  auto past_limit = [&] {
    return options.time_limit > 0 &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > options.time_limit;
  };
  for_each_index(tasks.size(), options.threads, [&](size_t k) {
    if (past_limit()) {
      timed_out = true;
      clusters[k] = skipped_cluster(f, tasks[k], "time limit");
    } else {
      clusters[k] = verify_cluster(f, tasks[k], options);
    }
    ++done;
    if (!options.progress) return;
    std::lock_guard lock(line_m);
    const auto now = std::chrono::steady_clock::now();
    if (now - last_line < std::chrono::seconds(1)) return;
    last_line = now;
    std::fprintf(stderr, "linkbox: verifying: %zu/%zu clusters, %.1f s\n", done.load(), tasks.size(),
                 std::chrono::duration<double>(now - t0).count());
  });
  VerifyReport report = conclude(f, std::move(clusters), result, options);
  report.timed_out = timed_out;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return report;
}

}  // namespace linkbox::verify
