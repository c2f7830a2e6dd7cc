#include "verify/certify_case.hpp"

#include "verify/cluster.hpp"
#include "prune/newton/square_system.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>

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

// A polynomial system of any shape in float arithmetic (midpoints of interval values at a
// point). It only chooses where to look and which equations to keep; it proves nothing.
class FloatSystem {
 public:
  FloatSystem(const std::vector<model::Polynomial>& f, size_t unknowns) : f_(f), df_(f.size()) {
    for (size_t i = 0; i < f.size(); ++i)
      for (size_t k = 0; k < unknowns; ++k) df_[i].push_back(f[i].derivative(static_cast<int>(k)));
  }
  Eigen::VectorXd values(const Eigen::VectorXd& x) const {
    const Box p = point_box(x);
    Eigen::VectorXd v(f_.size());
    for (size_t i = 0; i < f_.size(); ++i) v(i) = median(f_[i].eval(p));
    return v;
  }
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& x) const {
    const Box p = point_box(x);
    Eigen::MatrixXd j(f_.size(), x.size());
    for (size_t i = 0; i < f_.size(); ++i)
      for (int k = 0; k < x.size(); ++k) j(i, k) = median(df_[i][k].eval(p));
    return j;
  }
  // Gauss-Newton with the pseudo-inverse: onto a curve, or the least-squares point of an
  // overdetermined system.
  Eigen::VectorXd solve_from(Eigen::VectorXd x) const {
    for (int it = 0; it < 30; ++it) x -= jacobian(x).completeOrthogonalDecomposition().solve(values(x));
    return x;
  }

 private:
  std::vector<model::Polynomial> f_;
  std::vector<std::vector<model::Polynomial>> df_;
};

// The k-th largest singular value (k >= 1): how well the rows span k dimensions.
double singular_value(const Eigen::MatrixXd& j, size_t k) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(j);
  const auto& sv = svd.singularValues();
  return static_cast<Eigen::Index>(k) <= sv.size() && k > 0 ? sv(k - 1) : 0;
}

// Whether the float Jacobian (at least as many equations as unknowns) is rank-deficient at a
// solution near the box's centre. A heuristic that only decides how to report a cluster.
bool rank_deficient_near(const std::vector<model::Polynomial>& f, const Box& x) {
  if (f.size() < x.size() || f.empty()) return false;
  const FloatSystem s(f, x.size());
  const Eigen::VectorXd p = s.solve_from(centre(x));
  if (!(s.values(p).norm() < 1e-9)) return false;
  const Eigen::MatrixXd j = s.jacobian(p);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(j);
  const auto& sv = svd.singularValues();
  return !(sv(sv.size() - 1) > 1e-6 * sv(0));
}

std::vector<int> rows_except(size_t count, const std::vector<int>& left_out) {
  std::vector<int> rows;
  for (int r = 0; r < static_cast<int>(count); ++r)
    if (std::find(left_out.begin(), left_out.end(), r) == left_out.end()) rows.push_back(r);
  return rows;
}

std::vector<model::Polynomial> pick(const std::vector<model::Polynomial>& f, const std::vector<int>& rows) {
  std::vector<model::Polynomial> out;
  for (int r : rows) out.push_back(f[r]);
  return out;
}

// Equations to leave out so that `keep` remain, chosen one at a time at the point p: each
// time the one whose removal leaves rows that best span `keep` dimensions (for a square
// system rank-deficient along a curve, keep = n - 1: the dependent equation).
std::vector<int> dependent_equations(const std::vector<model::Polynomial>& f, const Eigen::VectorXd& p,
                                     size_t keep) {
  const Eigen::MatrixXd j = FloatSystem(f, p.size()).jacobian(p);
  std::vector<int> dropped;
  while (f.size() - dropped.size() > keep) {
    int best = -1;
    double best_sv = -1;
    for (int r = 0; r < j.rows(); ++r) {
      if (std::find(dropped.begin(), dropped.end(), r) != dropped.end()) continue;
      auto without = dropped;
      without.push_back(r);
      const auto rows = rows_except(f.size(), without);
      Eigen::MatrixXd rest(rows.size(), j.cols());
      for (size_t k = 0; k < rows.size(); ++k) rest.row(k) = j.row(rows[k]);
      const double sv = singular_value(rest, keep);
      if (sv > best_sv) best_sv = sv, best = r;
    }
    dropped.push_back(best);
  }
  return dropped;
}

// Square subsystems of an overdetermined system to try, best first: the rows a pivoted QR
// of the Jacobian's transpose keeps at the point p, then, when one equation is extra, each
// other choice of the one to leave out.
std::vector<std::vector<int>> square_subsystems(const std::vector<model::Polynomial>& f, const Eigen::VectorXd& p) {
  const Eigen::MatrixXd j = FloatSystem(f, p.size()).jacobian(p);
  std::vector<std::vector<int>> out;
  if (j.allFinite()) {
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(j.transpose());
    std::vector<int> rows;
    for (int k = 0; k < p.size(); ++k) rows.push_back(qr.colsPermutation().indices()(k));
    std::sort(rows.begin(), rows.end());
    out.push_back(rows);
  }
  if (f.size() == static_cast<size_t>(p.size()) + 1)
    for (int r = static_cast<int>(f.size()); r-- > 0;) {
      auto rows = rows_except(f.size(), {r});
      if (std::find(out.begin(), out.end(), rows) == out.end()) out.push_back(rows);
    }
  return out;
}

std::string not_square(size_t equations, size_t unknowns) {
  return "natural system not square: " + std::to_string(equations) + " equations in " + std::to_string(unknowns) +
         " unknowns";
}

std::string count(size_t n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// A natural system that is not square certifies nothing, but can still prove a cluster
// empty: an equation whose range over the cluster misses 0, or (more equations than
// unknowns) a square subsystem whose Newton image misses it. Otherwise, with more equations
// than unknowns, a square subsystem with a unique root in the cluster and the other
// equations containing 0 there is said so: a consistent candidate, never a certified root
// (the other equations are only evaluated, and a root of the subsystem need not be one of
// them all).
void examine_not_square(const formulate::NaturalSystem& sys, const Box& start, ClusterReport& c,
                        const NewtonOptions& options) {
  const size_t e = sys.equations.size(), u = sys.unknowns.size();
  c.reason = not_square(e, u) + (e < u ? " (fewer equations: mobile)" : "");
  for (size_t i = 0; i < e; ++i)
    if (!zero_in(sys.equations[i].eval(start))) {
      c.status = ClusterStatus::empty;
      c.excluding_equation = static_cast<int>(i);
      c.certificate.box = start;
      c.reason = "proved to hold no root: natural equation " + std::to_string(i) + " misses 0 over the cluster";
      return;
    }
  if (e < u) return;
  // The least-squares point nearest the centre: where subsystems are chosen, and a start for
  // Newton when the centre leads elsewhere (a subsystem has roots the others do not share).
  const Eigen::VectorXd p = FloatSystem(sys.equations, u).solve_from(centre(start));
  Box near_p;
  if (p.allFinite())
    for (int k = 0; k < p.size(); ++k) near_p.push_back(Interval(p(k)) + Interval(-1e-6, 1e-6) * (1 + std::fabs(p(k))));
  for (const auto& rows : square_subsystems(sys.equations, p)) {
    const auto eqs = pick(sys.equations, rows);
    Certificate cert = certify_root(eqs, start, sys.domain, options);
    if (cert.reason == Reason::no_root) {
      c.status = ClusterStatus::empty;
      c.subsystem = rows;
      c.certificate = std::move(cert);
      c.reason = "proved to hold no root: the Newton image of " + std::to_string(u) + " of the " + std::to_string(e) +
                 " natural equations misses the cluster";
      return;
    }
    if (cert.status != Status::certified && !near_p.empty()) {
      Certificate from_p = certify_root(eqs, near_p, sys.domain, options);
      if (from_p.status == Status::certified && overlaps(from_p.image, start)) cert = std::move(from_p);
      else if (from_p.status == Status::certified)
        c.reason = "overdetermined: " + std::to_string(u) + " of " + count(e, "equation", "equations") +
                   " have a root next to the cluster, none found in it (not proved empty)";
    }
    if (cert.status != Status::certified) continue;
    bool others_vanish = true;
    for (int r : rows_except(e, rows)) others_vanish = others_vanish && zero_in(sys.equations[r].eval(cert.box));
    if (!others_vanish) continue;
    std::ostringstream w;
    w << std::setprecision(2) << max_width(cert.box);
    const std::string consistent = "overdetermined: " + std::to_string(u) + " of " + count(e, "equation", "equations") +
                 " have a unique root in the box; the other " + count(e - u, "contains", "contain") +
                 " 0 there (width " + w.str() + ")";
    c.subsystem = rows;
    c.certificate = std::move(cert);
    c.reason = consistent;
    return;
  }
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
    // n - 1 equations make a curve; the others are left out.
    const size_t n = sys.unknowns.size();
    if (sys.equations.size() >= n) x.dropped_equations = dependent_equations(sys.equations, centre(natural), n - 1);
    const auto eqs = pick(sys.equations, rows_except(sys.equations.size(), x.dropped_equations));
    // Fix the variable that varies most across the box (the curve's direction there).
    x.certificate = certify_curve_crossing(eqs, natural, widest_dimension(natural), options);
    // A crossing of the subsystem is a point of the solution set only where the equations
    // left out vanish too; near an ill-conditioned isolated root they do not.
    for (int d : x.dropped_equations)
      if (x.certificate.status == Status::certified && !zero_in(sys.equations[d].eval(x.certificate.box)))
        x.certificate.status = Status::unverified;
    c.crossings_certified += x.certificate.status == Status::certified;
    c.crossings.push_back(std::move(x));
  }
}

// Reasons are counted in the headline without their trailing detail in parentheses.
std::string without_detail(const std::string& reason) {
  const size_t open = reason.rfind(" (");
  return !reason.empty() && reason.back() == ')' && open != std::string::npos ? reason.substr(0, open) : reason;
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
    if (!start.empty() && n == 0) {
      c.reason = "no natural system to certify in" + (sys.missing.empty() ? "" : ": " + sys.missing);
    } else if (!start.empty() && !square) {
      examine_not_square(sys, start, c, options.newton);
    } else if (!start.empty()) {
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
    for (size_t k = 0; n > 0 && sys.equations.size() >= n && !rank_deficient && k < member.size();
         k += std::max<size_t>(1, member.size() / 5)) {
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
      if (!c.certificate.unique_in_hull) reasons[without_detail(c.reason)]++;
    } else if (c.status == ClusterStatus::curve) {
      report.curves++;
    } else if (c.status == ClusterStatus::empty) {
      report.empty++;
    } else if (c.status == ClusterStatus::unverified) {
      report.unverified++;
      reasons[without_detail(c.reason)]++;
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
    if (report.empty) report.headline += ", " + std::to_string(report.empty) + " proved empty";
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
