#include "verify/curve.hpp"

#include "newton/float_system.hpp"
#include "verify/subsystem.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <map>

namespace linkbox::verify {

namespace {

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
  const newton::FloatSystem s(f, x.size());
  const Eigen::VectorXd p = s.solve_from(newton::centre(x));
  if (!(s.values(p).norm() < 1e-9)) return false;
  const Eigen::MatrixXd j = s.jacobian(p);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(j);
  const auto& sv = svd.singularValues();
  return !(sv(sv.size() - 1) > 1e-6 * sv(0));
}

// Equations to leave out so that `keep` remain, chosen one at a time at the point p: each
// time the one whose removal leaves rows that best span `keep` dimensions (for a square
// system rank-deficient along a curve, keep = n - 1: the dependent equation).
std::vector<int> dependent_equations(const newton::FloatSystem& f, const Eigen::VectorXd& p, size_t keep) {
  const Eigen::MatrixXd j = f.jacobian(p);
  const size_t rows_total = static_cast<size_t>(j.rows());
  std::vector<int> dropped;
  while (rows_total - dropped.size() > keep) {
    int best = -1;
    double best_sv = -1;
    for (int r = 0; r < j.rows(); ++r) {
      if (std::find(dropped.begin(), dropped.end(), r) != dropped.end()) continue;
      auto without = dropped;
      without.push_back(r);
      const auto rows = rows_except(rows_total, without);
      Eigen::MatrixXd rest(rows.size(), j.cols());
      for (size_t k = 0; k < rows.size(); ++k) rest.row(k) = j.row(rows[k]);
      const double sv = singular_value(rest, keep);
      if (sv > best_sv) best_sv = sv, best = r;
    }
    dropped.push_back(best);
  }
  return dropped;
}

// A curve crossing of one member: in the member's chart, with one equation dropped where the
// Jacobian is rank deficient, the unknown that varies most fixed at the middle of the box.
// Members share a few charts and dropped sets: their systems are built once (building one
// differentiates every equation, which cost more than the Newton tests themselves).
class CrossingCertifier {
 public:
  CrossingCertifier(const formulate::Formulation& f, const std::vector<Box>& members,
                    const std::vector<std::uint64_t>& charts, const newton::NewtonOptions& options)
      : f_(f), members_(members), charts_(charts), options_(options) {}

  CurveCrossing operator()(size_t k) {
    CurveCrossing x;
    x.box = k;
    x.chart = charts_[k];
    const auto& sys = f_.natural(x.chart);
    Box natural;
    try {
      natural = f_.output_to_natural(x.chart, members_[k]);
    } catch (const std::exception&) {
      return x;
    }
    // n - 1 equations make a curve; the others are left out.
    const size_t n = sys.unknowns.size();
    if (sys.equations.size() >= n) {
      auto fs = floats_.try_emplace(x.chart, sys.equations, n).first;
      x.dropped_equations = dependent_equations(fs->second, newton::centre(natural), n - 1);
    }
    auto& eqs = compiled_[{x.chart, x.dropped_equations}];
    if (!eqs)
      eqs = std::make_shared<const model::CompiledSystem>(
          pick(sys.equations, rows_except(sys.equations.size(), x.dropped_equations)), n);
    // Fix the variable that varies most across the box (the curve's direction there).
    x.certificate = newton::certify_curve_crossing(eqs, natural, widest_dimension(natural), options_);
    // A crossing of the subsystem is a point of the solution set only where the equations
    // left out vanish too; near an ill-conditioned isolated root they do not.
    for (int d : x.dropped_equations)
      if (x.certificate.status == newton::Status::certified && !zero_in(sys.equations[d].eval(x.certificate.box)))
        x.certificate.status = newton::Status::unverified;
    return x;
  }

 private:
  const formulate::Formulation& f_;
  const std::vector<Box>& members_;
  const std::vector<std::uint64_t>& charts_;
  const newton::NewtonOptions& options_;
  std::map<std::uint64_t, newton::FloatSystem> floats_;
  std::map<std::pair<std::uint64_t, std::vector<int>>, std::shared_ptr<const model::CompiledSystem>> compiled_;
};

// Members certified first, spread evenly over the cluster, in two rounds, and how many of each
// round must pass for the rest to be tried. A cluster is called a curve only when crossings
// cover half of its boxes; a chain of boxes along a singular set that is not a curve of the
// subsystem (the cyclohexane's sigma-0.1 cluster: 313 boxes, 0.19 s of crossing attempts,
// most failing) is told from a curve by the first round, at a sixteenth of the cost. Where a
// quarter passes, a second round of 64 asks for a third: bicyclohexane's two 1 061-box
// clusters passed the first round (20-25% pass) and then failed in full, 3 s each. A curve's
// crossings pass far above that: nearly everywhere on the mobile 6R, half of gimbal lock's
// square boxes under `newton` (the circle clips some at a corner only, missing their mid-plane).
struct SampleRound {
  size_t size, needed;
};
constexpr SampleRound kCurveSample[] = {{16, 4}, {64, 22}};

// Certifies member by member that a solution curve crosses it; false (`c` then holds a part,
// for the caller to drop) when a sample round passes too rarely for crossings to be likely
// to cover half of the boxes, or once they no longer can. Only how the cluster is reported
// depends on it: every crossing listed is certified in full.
bool certify_curve(const formulate::Formulation& f, const std::vector<Box>& members,
                   const std::vector<std::uint64_t>& charts, ClusterReport& c, const newton::NewtonOptions& options) {
  CrossingCertifier cross(f, members, charts, options);
  const size_t size = c.boxes.size();
  std::map<size_t, CurveCrossing> sample;
  for (const SampleRound& round : kCurveSample) {
    if (size <= 2 * round.size) break;
    size_t passed = 0;
    for (size_t s = 0; s < round.size; ++s) {
      const size_t k = s * size / round.size;  // the earlier rounds' members among them
      auto it = sample.find(k);
      if (it == sample.end()) it = sample.emplace(k, cross(k)).first;
      passed += it->second.certificate.status == newton::Status::certified;
    }
    if (passed < round.needed) return false;
  }
  size_t failed = 0;
  for (auto& [k, x] : sample) failed += x.certificate.status != newton::Status::certified;
  for (size_t k = 0; k < size; ++k) {
    if (2 * failed > size) return false;
    auto it = sample.find(k);
    const bool sampled = it != sample.end();
    CurveCrossing x = sampled ? std::move(it->second) : cross(k);
    const bool certified = x.certificate.status == newton::Status::certified;
    failed += !sampled && !certified;
    c.crossings_certified += certified;
    c.crossings.push_back(std::move(x));
  }
  return true;
}

}  // namespace

bool classify_curve(const formulate::Formulation& f, const std::vector<Box>& member,
                    bool chart_holds_cluster, ClusterReport& c, const newton::NewtonOptions& options) {
  if (c.status != ClusterStatus::unverified) return false;
  const auto& sys = f.natural(c.chart);
  if (!sys.links.empty()) return false;  // curves are certified in polynomial equations only
  const size_t n = sys.unknowns.size();
  // Curve: many boxes spanning far more than any one of them, with a rank-deficient
  // Jacobian near the boxes (or fewer equations than unknowns).
  double box_width = 0;
  for (auto& b : member) box_width = std::max(box_width, max_width(b));
  // Below ~1e-6 a curve cannot be told from an ill-conditioned isolated root in double
  // precision (a root's enclosure stretches by eps / sigma_min): such clusters stay
  // unverified rather than be called curves.
  const bool long_cluster = c.boxes.size() >= 4 && max_width(c.hull) > 2 * box_width && max_width(c.hull) > 1e-6;
  if (!long_cluster) return false;  // before the rank test: its SVDs are O(n^3)
  // Members are analysed in the cluster's chart when it holds the whole cluster, else
  // each in its own: a curve that winds around a whole turn (gimbal lock) fits no single
  // chart of half-angle tangents, but every small box does.
  std::vector<std::uint64_t> charts(member.size(), c.chart);
  if (!chart_holds_cluster)
    for (size_t k = 0; k < member.size(); ++k) charts[k] = f.chart_for(member[k]);
  bool rank_deficient = sys.equations.size() + 1 == n;
  for (size_t k = 0; n > 0 && sys.equations.size() >= n && !rank_deficient && k < member.size();
       k += std::max<size_t>(1, member.size() / 5)) {
    try {
      rank_deficient = rank_deficient_near(f.natural(charts[k]).equations, f.output_to_natural(charts[k], member[k]));
    } catch (const std::exception&) {
    }
  }
  if (!rank_deficient) return false;
  // Called a curve only when a solution curve of the subsystem, on which the dropped
  // equation vanishes, crosses at least half of its boxes; a singular isolated root (a
  // double root, an ill-conditioned one) does not, and stays unverified.
  ClusterReport curve = c;
  if (certify_curve(f, member, charts, curve, options) &&
      2 * static_cast<size_t>(curve.crossings_certified) >= curve.boxes.size()) {
    c = std::move(curve);
    c.status = ClusterStatus::curve;
    c.reason = chart_holds_cluster
                   ? "positive-dimensional: boxes follow a curve"
                   : "positive-dimensional: boxes follow a curve around a whole turn (each box in its own chart)";
  }
  return true;
}

}  // namespace linkbox::verify
