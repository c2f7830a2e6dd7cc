#include "verify/certify_case.hpp"

#include "verify/cluster.hpp"
#include "prune/newton/square_system.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

namespace linkbox::verify {

const char* to_string(ClusterStatus s) {
  switch (s) {
    case ClusterStatus::certified: return "certified";
    case ClusterStatus::unverified: return "unverified";
    case ClusterStatus::curve: return "curve";
    case ClusterStatus::empty: return "empty";
  }
  return "?";
}

namespace {

// Shifts angle dimensions of `b` by whole turns towards `ref` (an exact set translation,
// enclosed with a rigorous 2 pi).
Box unwrap(const Box& b, const Box& ref, bool angles) {
  if (!angles) return b;
  Box r = b;
  for (size_t i = 0; i < b.size(); ++i) {
    const double turns = std::round((median(ref[i]) - median(b[i])) / (2 * M_PI));
    if (turns != 0) r[i] += two_pi() * Interval(turns);
  }
  return r;
}

Eigen::VectorXd centre(const Box& b) {
  Eigen::VectorXd c(b.size());
  for (size_t i = 0; i < b.size(); ++i) c(i) = median(b[i]);
  return c;
}

// Whether the float Jacobian is rank-deficient at a solution near the box's centre (reached
// by Gauss-Newton with the pseudo-inverse, which converges onto a curve). A heuristic that
// only decides how to report a cluster; it proves nothing.
bool rank_deficient_near(const std::vector<model::Polynomial>& f, const Box& x) {
  if (f.size() != x.size() || f.empty()) return false;
  auto s = SquareSystem::all_unknown(f, x.size());
  Eigen::VectorXd p = centre(x);
  for (int it = 0; it < 30; ++it) p -= s.jacobian_at(p).completeOrthogonalDecomposition().solve(s.values_at(p));
  if (!(s.values_at(p).norm() < 1e-9)) return false;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(s.jacobian_at(p));
  const auto& sv = svd.singularValues();
  return !(sv(sv.size() - 1) > 1e-6 * sv(0));
}

// For a square system that is rank-deficient along a curve, the equation whose removal
// leaves the best-conditioned rows at x.
int dependent_equation(const std::vector<model::Polynomial>& f, const Box& x) {
  auto s = SquareSystem::all_unknown(f, x.size());
  const Eigen::MatrixXd j = s.jacobian_at(centre(x));
  int best = -1;
  double best_sv = -1;
  for (int r = 0; r < j.rows(); ++r) {
    Eigen::MatrixXd rest(j.rows() - 1, j.cols());
    for (int k = 0, o = 0; k < j.rows(); ++k)
      if (k != r) rest.row(o++) = j.row(k);
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(rest);
    const double sv = svd.singularValues()(svd.singularValues().size() - 1);
    if (sv > best_sv) best_sv = sv, best = r;
  }
  return best;
}

// Certifies member by member that a solution curve crosses it: in the member's chart, with
// one equation dropped where the Jacobian is rank deficient, the unknown that varies most
// fixed at the middle of the box.
void certify_curve(const formulate::Formulation& f, formulate::NaturalSystems& systems,
                   const std::vector<Box>& members, const std::vector<std::uint64_t>& charts, ClusterReport& c,
                   const NewtonOptions& options) {
  for (size_t k = 0; k < c.boxes.size(); ++k) {
    CurveCrossing x;
    x.box = k;
    x.chart = charts[k];
    const auto& sys = systems(x.chart);
    Box natural;
    try {
      natural = f.output_to_natural(x.chart, members[k]);
    } catch (const std::exception&) {
      c.crossings.push_back(x);
      continue;
    }
    std::vector<model::Polynomial> eqs = sys.equations;
    if (eqs.size() == sys.unknowns.size()) {
      x.dropped_equation = dependent_equation(eqs, natural);
      eqs.erase(eqs.begin() + x.dropped_equation);
    }
    x.certificate = certify_curve_crossing(eqs, natural, widest_dimension(natural), options);
    // A crossing of the square subsystem is a point of the solution set only where the
    // dropped equation vanishes too; near an ill-conditioned isolated root it does not.
    if (x.certificate.status == Status::certified && x.dropped_equation >= 0 &&
        !zero_in(sys.equations[x.dropped_equation].eval(x.certificate.box)))
      x.certificate.status = Status::unverified;
    c.crossings_certified += x.certificate.status == Status::certified;
    c.crossings.push_back(std::move(x));
  }
}

}  // namespace

VerifyReport verify_case(const formulate::Formulation& f, const solve::CaseResult& result,
                         const VerifyOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  VerifyReport report;
  const bool angles = f.outputs_are_angles();
  std::vector<Box> outputs;
  std::vector<std::pair<size_t, size_t>> where;
  std::vector<double> residual;
  for (auto& s : result.subproblems) {
    if (s.solutions.empty()) continue;
    const auto equations = f.subproblem(s.index).system.equations;
    for (size_t k = 0; k < s.solutions.size(); ++k) {
      outputs.push_back(f.to_output(s.index, s.solutions[k]));
      where.emplace_back(s.index, k);
      residual.push_back(model::residual_bound(equations, s.solutions[k]));
    }
  }
  const std::vector<bool> periodic(f.output_names().size(), angles);
  const auto groups = cluster_boxes(outputs, periodic);

  formulate::NaturalSystems systems(f);
  std::vector<Box> roots;        // certified root boxes (output variables), for merging
  std::vector<size_t> root_of;   // cluster index of each
  for (auto& g : groups) {
    ClusterReport c;
    std::vector<Box> member;
    for (int i : g) {
      c.boxes.push_back(where[i]);
      member.push_back(unwrap(outputs[i], outputs[g[0]], angles));
      c.max_residual = std::max(c.max_residual, residual[i]);
    }
    c.hull = member[0];
    for (auto& b : member) c.hull = hull(c.hull, b);
    c.chart = f.chart_for(c.hull);
    const auto& sys = systems(c.chart);
    const size_t n = sys.unknowns.size();
    Box start;
    try {
      start = f.output_to_natural(c.chart, c.hull);
    } catch (const std::exception& e) {
      c.reason = std::string("cluster too wide for a chart: ") + e.what();
    }
    const bool square = n > 0 && sys.equations.size() == n;
    if (!start.empty() && square) {
      c.certificate = certify_root(sys.equations, start, sys.domain, options.newton);
      if (c.certificate.status == Status::certified && !c.certificate.root_in_domain && !sys.domain.empty()) {
        c.reason = "root on the domain boundary: certified in a slightly enlarged domain only";
      } else if (c.certificate.status == Status::certified) {
        c.status = ClusterStatus::certified;
        c.root = f.natural_to_output(c.chart, c.certificate.box);
        c.outputs = f.natural_outputs(c.chart, c.certificate.box);
        for (auto& b : member) c.distances.push_back(farthest_distance(b, c.root, periodic));
        c.max_distance = *std::max_element(c.distances.begin(), c.distances.end());
        if (!c.certificate.unique_in_hull) c.reason = "root certified; its cluster hull not proved free of other roots";
      } else if (c.certificate.reason == Reason::no_root) {
        c.status = ClusterStatus::empty;
        c.reason = "proved to hold no root: the Newton image misses the cluster";
      } else {
        c.reason = to_string(c.certificate.reason);
      }
    } else if (!start.empty()) {
      c.reason = n == 0 ? "no natural system to certify in"
                        : "natural system not square (" + std::to_string(sys.equations.size()) + " equations, " +
                              std::to_string(n) + " unknowns)";
    }
    // Curve: many boxes spanning far more than any one of them, with a rank-deficient
    // Jacobian near the boxes (or fewer equations than unknowns).
    double box_width = 0;
    for (auto& b : member) box_width = std::max(box_width, max_width(b));
    // Below ~1e-6 a curve cannot be told from an ill-conditioned isolated root in double
    // precision (a root's enclosure stretches by eps / sigma_min): such clusters stay
    // unverified rather than be called curves.
    const bool long_cluster = c.boxes.size() >= 4 && max_width(c.hull) > 2 * box_width && max_width(c.hull) > 1e-6;
    // Members are analysed in the cluster's chart when it holds the whole cluster, else
    // each in its own: a curve that winds around a whole turn (gimbal lock) fits no single
    // chart of half-angle tangents, but every small box does.
    std::vector<std::uint64_t> charts(member.size(), c.chart);
    if (start.empty())
      for (size_t k = 0; k < member.size(); ++k) charts[k] = f.chart_for(member[k]);
    bool rank_deficient = sys.equations.size() + 1 == n;
    for (size_t k = 0; square && !rank_deficient && k < member.size(); k += std::max<size_t>(1, member.size() / 5)) {
      try {
        rank_deficient = rank_deficient_near(systems(charts[k]).equations, f.output_to_natural(charts[k], member[k]));
      } catch (const std::exception&) {
      }
    }
    if (c.status == ClusterStatus::unverified && long_cluster && rank_deficient) {
      // Called a curve only when a solution curve of the subsystem, on which the dropped
      // equation vanishes, crosses at least half of its boxes; a singular isolated root (a
      // double root, an ill-conditioned one) does not, and stays unverified.
      ClusterReport curve = c;
      certify_curve(f, systems, member, charts, curve, options.newton);
      if (2 * static_cast<size_t>(curve.crossings_certified) >= curve.boxes.size()) {
        c = std::move(curve);
        c.status = ClusterStatus::curve;
        c.reason = start.empty() ? "positive-dimensional: boxes follow a curve around a whole turn (each box in its own chart)"
                                 : "positive-dimensional: boxes follow a curve";
      }
    }
    if (c.status == ClusterStatus::certified) {
      roots.push_back(c.root);
      root_of.push_back(report.clusters.size());
    }
    report.clusters.push_back(std::move(c));
  }

  // Two clusters whose certified roots overlap are the same root when one certificate
  // covers both boxes; otherwise both stay, and the run is not exact.
  std::vector<bool> duplicate(report.clusters.size(), false);
  int overlaps_unresolved = 0;
  for (auto& g : cluster_boxes(roots, periodic)) {
    if (g.size() < 2) continue;
    ClusterReport& first = report.clusters[root_of[g[0]]];
    for (size_t k = 1; k < g.size(); ++k) {
      ClusterReport& other = report.clusters[root_of[g[k]]];
      const auto& sys = systems(first.chart);
      Box joint = first.certificate.box;
      try {
        joint = hull(joint, f.output_to_natural(first.chart, unwrap(other.root, first.root, angles)));
      } catch (const std::exception&) {
      }
      Certificate both = certify_root(sys.equations, joint, sys.domain, options.newton);
      if (both.status == Status::certified && both.unique_in_hull) {
        duplicate[root_of[g[k]]] = true;
        other.duplicate_of = static_cast<int>(root_of[g[0]]);
        other.reason = "same root as another cluster (found by two sub-problems)";
      } else {
        ++overlaps_unresolved;
      }
    }
  }
  bool all_unique = true;
  std::map<std::string, int> reasons;
  for (size_t i = 0; i < report.clusters.size(); ++i) {
    auto& c = report.clusters[i];
    if (c.status == ClusterStatus::certified && !duplicate[i]) {
      report.certified_roots++;
      all_unique = all_unique && c.certificate.unique_in_hull;
      if (!c.certificate.unique_in_hull) reasons[c.reason]++;
    } else if (c.status == ClusterStatus::curve) {
      report.curves++;
    } else if (c.status == ClusterStatus::empty) {
      report.empty++;
    } else if (c.status == ClusterStatus::unverified) {
      report.unverified++;
      reasons[c.reason]++;
    }
  }
  report.exact = result.complete && result.rigorous && report.unverified == 0 && report.curves == 0 && all_unique &&
                 overlaps_unresolved == 0;
  const int n = report.certified_roots;
  if (report.exact) {
    report.headline = "exactly " + std::to_string(n) + " root" + (n == 1 ? "" : "s") +
                      " in the domain, each in its certified box";
  } else {
    report.headline = std::to_string(n) + " certified";
    if (report.curves) report.headline += ", " + std::to_string(report.curves) + " curve cluster(s)";
    if (report.unverified) report.headline += ", " + std::to_string(report.unverified) + " unresolved";
    if (overlaps_unresolved) report.headline += ", " + std::to_string(overlaps_unresolved) + " overlapping roots unresolved";
    if (!result.complete) report.headline += "; search incomplete (" + result.stop_reason + ")";
    if (!result.rigorous) report.headline = "UNVERIFIED search (--arith float: boxes were discarded on float evidence, roots may be missing): " + report.headline;
    std::string why;
    for (auto& [r, k] : reasons) why += (why.empty() ? "" : "; ") + r + " x" + std::to_string(k);
    if (!why.empty()) report.headline += " (" + why + ")";
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return report;
}

}  // namespace linkbox::verify
