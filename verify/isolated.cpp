#include "verify/isolated.hpp"

#include "verify/exact_point.hpp"

#include "newton/float_system.hpp"
#include "verify/check_proofs.hpp"
#include "verify/cluster.hpp"
#include "verify/coupled_loops.hpp"
#include "verify/subsystem.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace linkbox::verify {

namespace {

// Square subsystems of an overdetermined system to try, best first: the rows a pivoted QR
// of the Jacobian's transpose keeps at the point p, then, when one equation is extra, each
// other choice of the one to leave out.
std::vector<std::vector<int>> square_subsystems(const std::vector<model::Polynomial>& f, const Eigen::VectorXd& p) {
  const Eigen::MatrixXd j = newton::FloatSystem(f, p.size()).jacobian(p);
  std::vector<std::vector<int>> out;
  if (j.allFinite()) out.push_back(newton::independent_rows(j));
  if (f.size() == static_cast<size_t>(p.size()) + 1)
    for (int r = static_cast<int>(f.size()); r-- > 0;) {
      auto rows = rows_except(f.size(), {r});
      if (std::find(out.begin(), out.end(), rows) == out.end()) out.push_back(rows);
    }
  return out;
}

}  // namespace

bool excludes(const formulate::NaturalSystem& sys, int e, const Box& box) {
  const int m = static_cast<int>(sys.equations.size());
  if (e < 0 || e >= m + static_cast<int>(sys.links.size())) return false;
  return e < m ? excludes_zero(sys.equations[e].eval(box)) : !model::may_hold(sys.links[e - m], box);
}

namespace {

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
// Links count as equations (numbered after the polynomials); their subsystems are not tried.
void examine_not_square(const formulate::NaturalSystem& sys, const Box& start, ClusterReport& c,
                        const newton::NewtonOptions& options) {
  const size_t e = sys.equations.size() + sys.links.size(), u = sys.unknowns.size();
  c.reason = not_square(e, u) + (e < u ? " (fewer equations: mobile)" : "");
  for (size_t i = 0; i < e; ++i)
    if (excludes(sys, static_cast<int>(i), start)) {
      c.status = ClusterStatus::empty;
      c.excluding_equation = static_cast<int>(i);
      c.certificate.box = start;
      c.reason = "proved to hold no root: natural equation " + std::to_string(i) + " misses 0 over the cluster";
      return;
    }
  if (e < u || !sys.links.empty()) return;
  // The least-squares point nearest the centre: where subsystems are chosen, and a start for
  // Newton when the centre leads elsewhere (a subsystem has roots the others do not share).
  const Eigen::VectorXd p = newton::FloatSystem(sys.equations, u).solve_from(newton::centre(start));
  Box near_p;
  if (p.allFinite())
    for (int k = 0; k < p.size(); ++k) near_p.push_back(Interval(p(k)) + Interval(-1e-6, 1e-6) * (1 + std::fabs(p(k))));
  for (const auto& rows : square_subsystems(sys.equations, p)) {
    const auto eqs = pick(sys.equations, rows);
    newton::Certificate cert = newton::certify_root(eqs, start, sys.domain, options);
    if (cert.reason == newton::Reason::no_root) {
      c.status = ClusterStatus::empty;
      c.subsystem = rows;
      c.certificate = std::move(cert);
      c.reason = "proved to hold no root: the Newton image of " + std::to_string(u) + " of the " + std::to_string(e) +
                 " natural equations misses the cluster";
      return;
    }
    if (cert.status != newton::Status::certified && !near_p.empty()) {
      newton::Certificate from_p = newton::certify_root(eqs, near_p, sys.domain, options);
      if (from_p.status == newton::Status::certified && overlaps(from_p.image, start)) cert = std::move(from_p);
      else if (from_p.status == newton::Status::certified)
        c.reason = "overdetermined: " + std::to_string(u) + " of " + count(e, "equation", "equations") +
                   " have a root next to the cluster, none found in it (not proved empty)";
    }
    if (cert.status != newton::Status::certified) continue;
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

// Sets c.exact_root, if not yet set, from the certified image; whether it is set. Links
// (y = f(a)) have no exact values at rationals, so only polynomial systems have exact roots.
bool find_exact_root(const formulate::NaturalSystem& sys, ClusterReport& c) {
  if (c.exact_root.empty() && sys.links.empty() && c.certificate.status == newton::Status::certified)
    if (auto p = exact_zero_in(sys.equations, c.certificate.image)) c.exact_root = std::move(*p);
  return !c.exact_root.empty();
}

}  // namespace

void accept_root(const formulate::Formulation& f, const std::vector<Box>& members, const std::vector<bool>& periodic,
                 ClusterReport& c) {
  c.status = ClusterStatus::certified;
  c.root = f.natural_to_output(c.chart, c.certificate.box);
  c.outputs = f.natural_outputs(c.chart, c.certificate.box);
  for (auto& b : members) c.distances.push_back(farthest_distance(b, c.root, periodic));
  c.max_distance = *std::max_element(c.distances.begin(), c.distances.end());
}

void certify_coupled(const formulate::Formulation& f, const Box& start, const std::vector<Box>& members,
                     const std::vector<bool>& periodic, ClusterReport& c) {
  const auto& sys = f.natural(c.chart);
  if (c.status == ClusterStatus::unverified && c.subsystem.empty() && sys.equations.size() > sys.unknowns.size()) {
    // No isolated root here: say what the loops leave when it is a curve.
    const CoupledLoops r = coupled_loops_root(f, c.chart, start, start);
    if (r.unknowns == r.equations + 1)
      c.reason += "; through its loops: " + r.how + ", a curve of the coupled loops, which no map follows yet";
    return;
  }
  if (c.status != ClusterStatus::unverified || c.subsystem.empty() || c.certificate.status != newton::Status::certified ||
      (!sys.domain.empty() && !c.certificate.root_in_domain))
    return;
  const CoupledRoom room = coupled_room(pick(sys.equations, c.subsystem), start, c.certificate);
  if (!room.unique) return;
  const CoupledLoops r = coupled_loops_root(f, c.chart, c.certificate.box, room.box);
  if (!r.proved) {
    if (!r.how.empty()) c.reason += "; not proved through its loops: " + r.how;
    return;
  }
  accept_root(f, members, periodic, c);
  c.certificate.unique_in_hull = room.cluster;
  c.argument = "coupled loops";
  c.reason = "certified through its loops: " + r.how + "; " +
             (room.cluster ? "no other root in the cluster: the " + std::to_string(c.subsystem.size()) +
                                 " equations of its square subsystem have only this one"
                           : "its cluster hull not proved free of other roots");
}

namespace {

// An overdetermined polynomial system whose square subsystem has a certified unique root in
// the box, at a rational point of its image where every natural equation is exactly 0: that
// point is the subsystem's root, so a root of every equation. The whole system's roots are
// among the subsystem's, so the subsystem's uniqueness around the cluster is the system's.
void certify_exact_overdetermined(const formulate::Formulation& f, const formulate::NaturalSystem& sys,
                                  const Box& start, const std::vector<Box>& members,
                                  const std::vector<bool>& periodic, ClusterReport& c) {
  if (c.status != ClusterStatus::unverified || c.subsystem.empty()) return;
  if (!find_exact_root(sys, c)) {
    if (f.kind() == "polynomial" && sys.links.empty() && !known_coefficients(sys.equations))
      c.reason += "; no exact root can be placed: some coefficients have no exact value (e.g. pi or sqrt(2))";
    return;
  }
  if (!sys.domain.empty() && !c.certificate.root_in_domain && !rationals_in(c.exact_root, sys.domain)) {
    c.exact_root.clear();  // a root of the system, but not proved in the domain: stays a candidate
    return;
  }
  c.certificate.root_in_domain = true;
  c.certificate.unique_in_hull = unique_over(pick(sys.equations, c.subsystem), start, c.certificate);
  accept_root(f, members, periodic, c);
  c.argument = "exact root";
  const size_t e = sys.equations.size(), u = sys.unknowns.size();
  c.reason = "certified: all " + count(e, "equation", "equations") + " are exactly 0 at a rational point of the box where " +
             std::to_string(u) + " of them have a unique root; " +
             (c.certificate.unique_in_hull ? "no other root in the cluster" : "its cluster hull not proved free of other roots");
}

}  // namespace

void certify_isolated(const formulate::Formulation& f, const formulate::NaturalSystem& sys, const Box& start,
                      const std::vector<Box>& members, const std::vector<bool>& periodic, ClusterReport& c,
                      const newton::NewtonOptions& options) {
  const size_t n = sys.unknowns.size();
  if (n == 0) {
    c.reason = "no natural system to certify in" + (sys.missing.empty() ? "" : ": " + sys.missing);
    return;
  }
  if (sys.equations.size() + sys.links.size() != n) {
    examine_not_square(sys, start, c, options);
    certify_exact_overdetermined(f, sys, start, members, periodic, c);
    return;
  }
  c.certificate = newton::certify_root(newton::SquareSystem::all_unknown(sys.compiled), start, sys.domain, options);
  if (c.certificate.status == newton::Status::certified && !c.certificate.root_in_domain && !sys.domain.empty() &&
      find_exact_root(sys, c) && rationals_in(c.exact_root, sys.domain))
    c.certificate.root_in_domain = true;
  if (c.certificate.status == newton::Status::certified && !c.certificate.root_in_domain && !sys.domain.empty()) {
    c.reason = "root on the domain boundary: certified in a slightly enlarged domain only";
  } else if (c.certificate.status == newton::Status::certified) {
    accept_root(f, members, periodic, c);
    if (!c.certificate.unique_in_hull) c.reason = "root certified; its cluster hull not proved free of other roots";
  } else if (c.certificate.reason == newton::Reason::no_root) {
    c.status = ClusterStatus::empty;
    c.reason = "proved to hold no root: the Newton image misses the cluster";
  } else {
    c.reason = to_string(c.certificate.reason);
  }
}

void classify_inequalities(const formulate::NaturalSystem& sys, const Box& start, ClusterReport& c) {
  const auto& ineqs = sys.inequalities;
  if (ineqs.empty() || c.status == ClusterStatus::empty || c.status == ClusterStatus::infeasible) return;
  const bool certified = c.status == ClusterStatus::certified;
  // Where the cluster's roots are: the certified box (exactly one root), else the hull.
  const Box& where = certified ? c.certificate.box : start;
  int outside = -1;
  bool exact_tried = false;  // an exact root is looked for once, at the first undecided side
  for (size_t k = 0; k < ineqs.size(); ++k) {
    model::Side side = model::side_of(ineqs[k], where);
    if (side == model::Side::boundary && certified) {
      if (!exact_tried) find_exact_root(sys, c);
      exact_tried = true;
      if (!c.exact_root.empty()) side = exact_side(ineqs[k], c.exact_root);
    }
    if (side == model::Side::boundary) c.straddled.push_back(static_cast<int>(k));
    if (side == model::Side::outside && outside < 0) outside = static_cast<int>(k);
  }
  const auto quoted = [&](int k) { return "\"" + ineqs[k].name + "\""; };
  if (outside >= 0) {
    c.inequality = outside;
    if (!certified) {
      if (c.status == ClusterStatus::curve) return;  // crossings stay; the curve is where the inequality fails
      c.status = ClusterStatus::infeasible;
      c.certificate = {};
      c.certificate.box = start;
      c.reason = "proved to hold no root where the inequalities hold: " + quoted(outside) + " fails on all of it";
    } else if (c.certificate.unique_in_hull) {
      c.status = ClusterStatus::infeasible;
      c.reason = "its only root violates " + quoted(outside);
    } else {
      c.status = ClusterStatus::unverified;
      c.reason = "its certified root violates " + quoted(outside) + "; the cluster hull is not proved free of other roots";
    }
    return;
  }
  if (c.straddled.empty()) return;
  if (certified) {
    c.inequality = c.straddled[0];
    c.status = ClusterStatus::unverified;
    c.reason = "root certified on an inequality's boundary (" + quoted(c.straddled[0]) +
               " is undecided on its certified box)";
  } else if (c.status == ClusterStatus::unverified) {
    // A reason is read in one line: the first few names, then how many more.
    constexpr size_t shown = 4;
    std::string list;
    for (size_t k = 0; k < c.straddled.size() && k < shown; ++k) list += (list.empty() ? "" : ", ") + quoted(c.straddled[k]);
    if (c.straddled.size() > shown) list += " and " + std::to_string(c.straddled.size() - shown) + " more";
    c.reason += (c.reason.empty() ? "" : "; ") + std::string("straddles ") + list;
  }
}

}  // namespace linkbox::verify
