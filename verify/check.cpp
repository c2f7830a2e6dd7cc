#include "verify/check.hpp"

#include "newton/certify.hpp"
#include "newton/interval_newton.hpp"
#include "verify/check_map.hpp"
#include "verify/cluster.hpp"

#include <Eigen/LU>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

namespace linkbox::verify {

using nlohmann::json;

namespace {

Box box_from(const json& j) {
  Box b;
  for (auto& x : j) b.push_back(Interval(x.at(0).get<double>(), x.at(1).get<double>()));
  return b;
}

newton::Certificate certificate_from(const json& j) {
  newton::Certificate c;
  const std::string method = j.at("method");
  if (method != "krawczyk" && method != "hansen-sengupta")
    throw std::invalid_argument("unknown certificate method '" + method + "'");
  c.method = method == "krawczyk" ? newton::Method::krawczyk : newton::Method::hansen_sengupta;
  c.box = box_from(j.at("box"));
  // Rows of one length, checked before anything is allocated or written.
  const json& m = j.at("preconditioner");
  const size_t cols = m.empty() ? 0 : m.at(0).size();
  for (size_t r = 0; r < m.size(); ++r)
    if (!m.at(r).is_array() || m[r].size() != cols)
      throw std::invalid_argument("a preconditioner whose rows differ in length");
  c.preconditioner.resize(m.size(), cols);
  for (size_t r = 0; r < m.size(); ++r)
    for (size_t k = 0; k < cols; ++k) c.preconditioner(r, k) = m[r][k].get<double>();
  c.fixed_variable = j.value("fixed_variable", -1);
  return c;
}

// Box inclusion that fails on a size mismatch (contains() of box.hpp reads `inner` by
// `outer`'s size): every box here comes from the file.
bool encloses(const Box& outer, const Box& inner) { return outer.size() == inner.size() && contains(outer, inner); }

// The Newton image of a certificate's box under its preconditioner, computed as
// newton::recheck computes it (a curve crossing: the variable fixed_variable held at its
// degenerate side). Empty when the test does not hold: the image is not strictly inside the
// box, or the sizes do not fit the equations.
std::optional<Box> proved_image(const std::vector<model::Polynomial>& f, const newton::Certificate& c) {
  const int n = static_cast<int>(c.box.size()), p = c.fixed_variable;
  if (n == 0 || p >= n || (p >= 0 && !(c.box[p].lower() == c.box[p].upper()))) return std::nullopt;
  std::vector<int> unknowns;
  for (int i = 0; i < n; ++i)
    if (i != p) unknowns.push_back(i);
  try {
    const newton::SquareSystem s(f, unknowns, c.box);
    const newton::NewtonStep step = newton::newton_step(c.method, s, s.restrict(c.box), c.preconditioner);
    if (!step.interior) return std::nullopt;
    return s.embed(step.image);
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

// unique_in_hull re-proved as newton::certify_root proves it: no root in hull(start, box)
// other than the certificate's. Either the box covers the start, or the Newton test with the
// certificate's C holds on the union itself (when certify_root certified its start whole and
// then tightened), or ||I - C F'|| < 1 over the union (F injective there) with that C or, as
// certify_root tries next, the inverse of the union's midpoint Jacobian (float, only chosen:
// any C makes either test a proof).
bool unique_over(const formulate::NaturalSystem& sys, const Box& start, const newton::Certificate& c) {
  if (encloses(c.box, start)) return true;
  if (c.box.size() != start.size() || start.size() != sys.unknowns.size()) return false;
  try {
    const newton::SquareSystem s = sys.compiled ? newton::SquareSystem::all_unknown(sys.compiled)
                                                : newton::SquareSystem::all_unknown(sys.equations, start.size());
    const Box y = hull(start, c.box);
    if (newton::newton_step(c.method, s, y, c.preconditioner).interior) return true;
    if (newton::at_most_one_root(s, y, c.preconditioner)) return true;
    const Eigen::MatrixXd jm = newton::midpoint(s.jacobian(y));
    if (jm.size() == 0 || !jm.allFinite()) return false;
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(jm);
    if (!(lu.rcond() >= newton::NewtonOptions{}.singular_rcond)) return false;
    const Eigen::MatrixXd cy = lu.inverse();
    return cy.allFinite() && newton::at_most_one_root(s, y, cy);
  } catch (const std::invalid_argument&) {
    return false;
  }
}

// A box carried between a chart's natural unknowns and the outputs (`map` does it); empty
// when it cannot be, e.g. an angle box too wide for the chart's half-angle tangents.
template <class Map>
std::optional<Box> carried(Map&& map) {
  try {
    return map();
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// The shift of each angle side by whole turns that brings `b` nearest `ref` (as clustering
// unwraps a cluster's boxes); `b` unchanged when outputs are not angles.
Box unwrapped(const Box& b, const Box& ref, bool angles) {
  if (!angles || b.size() != ref.size()) return b;
  Box r = b;
  for (size_t i = 0; i < b.size(); ++i) {
    const double turns = std::round((median(ref[i]) - median(b[i])) / (2 * M_PI));
    if (turns != 0) r[i] += two_pi() * Interval(turns);
  }
  return r;
}

// The natural equations a certificate speaks of: those listed under `key`, or all of them.
// Returns false when an index is out of range.
bool equations_named(const json& c, const char* key, const std::vector<model::Polynomial>& all,
                     std::vector<model::Polynomial>& out) {
  if (!c.contains(key)) {
    out = all;
    return true;
  }
  out.clear();
  for (auto& r : c.at(key)) {
    const int i = r.get<int>();
    if (i < 0 || i >= static_cast<int>(all.size())) return false;
    out.push_back(all[i]);
  }
  return true;
}

// Whether `hull` covers `b`, angle sides modulo whole turns.
bool covers(const Box& hull, const Box& b, bool angles) {
  if (hull.size() != b.size()) return false;
  for (size_t i = 0; i < b.size(); ++i) {
    bool in = contains(hull[i], b[i].lower()) && contains(hull[i], b[i].upper());
    for (int k = -1; angles && !in && k <= 1; k += 2) {
      const Interval s = b[i] + two_pi() * Interval(k);
      in = hull[i].lower() <= s.lower() && s.upper() <= hull[i].upper();
    }
    if (!in) return false;
  }
  return true;
}
}  // namespace

CheckOutcome check_certificates(const json& j, const formulate::Formulation& f) {
  CheckOutcome out;
  const size_t outputs = f.output_names().size();
  const bool angles = f.outputs_are_angles();
  // A result for other variables is not this case's (the names are all a result states).
  if (j.contains("variables") && j.at("variables") != f.output_names())
    out.failures.push_back("the result's variables are not the case's");
  // Charts are masks of half-turn shifts of the angle outputs; other formulations have one.
  const auto chart_exists = [&](std::uint64_t chart) {
    return angles ? outputs >= 64 || chart >> outputs == 0 : chart == 0;
  };
  // Solution boxes by (sub-problem, index within it), to check that hulls cover members.
  std::map<std::pair<size_t, size_t>, Box> solutions;
  std::map<size_t, size_t> seen;
  for (auto& s : j.at("solutions")) {
    const size_t sub = s.at("subproblem");
    solutions[{sub, seen[sub]++}] = box_from(s.at("box"));
  }
  // Every solution box must be a member of exactly one cluster: a box left out of every
  // cluster (or a cluster left out) could hold a root the count never sees.
  std::map<std::pair<size_t, size_t>, size_t> owner;
  std::vector<size_t> duplicates;  // certified clusters marked duplicate_of another
  std::vector<size_t> proved_maps;  // curve clusters whose map re-proves as proved
  std::vector<CurveMap> proved_map_data;
  int certified = 0, closed_curves = 0, open_arcs = 0;
  const std::vector<bool> periodic(outputs, angles);
  const auto& clusters = j.at("clusters");
  for (size_t i = 0; i < clusters.size(); ++i) {
    const json& c = clusters[i];
    const std::string where = "cluster " + std::to_string(i);
    const std::string status = c.at("status");
    const auto chart = c.at("chart").get<std::uint64_t>();
    const Box hull = box_from(c.at("hull"));
    for (auto& m : c.at("members")) {
      const std::pair<size_t, size_t> key{m.at(0).get<size_t>(), m.at(1).get<size_t>()};
      auto it = solutions.find(key);
      if (it == solutions.end() || !covers(hull, it->second, angles))
        out.failures.push_back(where + ": its hull does not cover its member solution boxes");
      else if (auto [at, fresh] = owner.emplace(key, i); !fresh)
        out.failures.push_back(where + ": lists a solution box that cluster " + std::to_string(at->second) +
                               " lists too");
    }
    if (hull.size() != outputs || !chart_exists(chart)) {
      out.failures.push_back(where + ": its hull or chart does not fit the case's " + std::to_string(outputs) +
                             " variables");
      continue;
    }
    const auto& sys = f.natural(chart);
    if (status == "certified") {
      ++out.checked;
      const json& cj = c.at("certificate");
      const newton::Certificate cert = certificate_from(cj);
      const std::optional<Box> image = proved_image(sys.equations, cert);
      if (!image) {
        out.failures.push_back(where + ": the Newton test does not hold on the stored box and preconditioner");
        continue;
      }
      // The stored image is the result's tightest enclosure of the root: it must hold the
      // image the box and preconditioner give (which holds the root).
      if (!encloses(box_from(cj.at("image")), *image))
        out.failures.push_back(where + ": the stored Newton image does not contain the one its box and preconditioner give");
      // The reported root must enclose what the certified box maps to.
      const auto root = carried([&] { return f.natural_to_output(chart, cert.box); });
      if (!root || !encloses(box_from(c.at("root")), *root))
        out.failures.push_back(where + ": the reported root box does not enclose the certified box");
      // A certified root must satisfy every inequality on its certified box.
      for (auto& q : sys.inequalities)
        if (model::side_of(q, cert.box) != model::Side::inside)
          out.failures.push_back(where + ": the certified root is not proved to satisfy \"" + q.name + "\"");
      if (!sys.domain.empty() && cj.value("root_in_domain", false) && !encloses(sys.domain, *image))
        out.failures.push_back(where + ": root claimed in the domain but its image is not");
      // "No other root in the cluster" is what makes a count exact: re-proved, not read.
      if (cj.value("unique_in_hull", false)) {
        const auto start = carried([&] { return f.output_to_natural(chart, hull); });
        if (!start || !unique_over(sys, *start, cert))
          out.failures.push_back(where + ": no other root in its hull is claimed but not proved");
      }
      if (!c.contains("duplicate_of")) ++certified;
      else duplicates.push_back(i);
    } else if (status == "empty") {
      ++out.checked;
      const json& cj = c.at("certificate");
      newton::Certificate cert = certificate_from(cj);
      std::vector<model::Polynomial> eqs;
      bool holds = cert.box.size() == sys.unknowns.size() && equations_named(c, "subsystem", sys.equations, eqs);
      if (holds && c.contains("excluding_equation")) {
        // Proved by evaluation: that equation's range over the box misses 0.
        const int k = c.at("excluding_equation");
        holds = k >= 0 && k < static_cast<int>(sys.equations.size()) && !zero_in(sys.equations[k].eval(cert.box));
      } else if (holds) {
        holds = newton::recheck_exclusion(eqs, cert.box, cert.preconditioner, cert.method);
      }
      if (!holds)
        out.failures.push_back(where + ": the proof that this cluster holds no root does not hold");
      else if (const auto start = carried([&] { return f.output_to_natural(chart, hull); });
               !start || !encloses(cert.box, *start))
        out.failures.push_back(where + ": the box proved empty does not cover the cluster");
    } else if (status == "infeasible") {
      // No root where the inequalities hold: one fails on the certified box of the cluster's
      // only root, or on a box that covers the cluster.
      ++out.checked;
      const newton::Certificate cert = certificate_from(c.at("certificate"));
      bool holds = cert.box.size() == sys.unknowns.size() &&
                   std::any_of(sys.inequalities.begin(), sys.inequalities.end(),
                               [&](auto& q) { return model::side_of(q, cert.box) == model::Side::outside; });
      const auto start = carried([&] { return f.output_to_natural(chart, hull); });
      if (c.at("certificate").at("status") == "certified")
        holds = holds && c.at("certificate").value("unique_in_hull", false) && newton::recheck(sys.equations, cert) &&
                start && unique_over(sys, *start, cert);
      else
        holds = holds && start && encloses(cert.box, *start);
      if (!holds) out.failures.push_back(where + ": the proof that this cluster holds no root satisfying the inequalities does not hold");
    } else if (status == "unverified" && c.contains("subsystem") && c.at("certificate").at("status") == "certified") {
      // An overdetermined system's square subsystem: its unique root is what the reason
      // speaks of, and the other equations contain 0 on its box.
      ++out.checked;
      std::vector<model::Polynomial> eqs;
      const newton::Certificate cert = certificate_from(c.at("certificate"));
      if (!equations_named(c, "subsystem", sys.equations, eqs) || !newton::recheck(eqs, cert)) {
        out.failures.push_back(where + ": the certificate of its square subsystem does not hold");
        continue;
      }
      for (size_t k = 0; k < sys.equations.size(); ++k)
        if (!zero_in(sys.equations[k].eval(cert.box))) {
          out.failures.push_back(where + ": natural equation " + std::to_string(k) + " misses 0 on the subsystem's box");
          break;
        }
    } else if (status == "curve") {
      if (c.contains("map")) {
        std::vector<Box> boxes;
        for (auto& m : c.at("members")) {
          auto it = solutions.find({m.at(0).get<size_t>(), m.at(1).get<size_t>()});
          // Unwrapped towards the first member, as verification unwrapped them.
          if (it != solutions.end()) boxes.push_back(boxes.empty() ? it->second : unwrapped(it->second, boxes[0], angles));
        }
        MapCheck mc = boxes.size() == c.at("members").size() ? check_map(c.at("map"), f, boxes, chart_exists)
                                                              : MapCheck{{"members missing"}, false, 0, 0, 0, {}};
        out.checked += mc.arcs;
        for (auto& why : mc.failures) out.failures.push_back(where + ": its map: " + why);
        if (mc.proved) {
          proved_map_data.push_back(std::move(mc.map));  // as re-proved, never as written
          proved_maps.push_back(i);
          closed_curves += mc.closed, open_arcs += mc.open;
        }
      }
      for (auto& x : c.at("crossings")) {
        if (x.at("status") != "certified") continue;
        ++out.checked;
        // Each crossing in its own chart: a curve around a whole turn fits no single one.
        const std::uint64_t crossing_chart = x.value("chart", chart);
        if (!chart_exists(crossing_chart)) {
          out.failures.push_back(where + ": a curve crossing names a chart the case does not have");
          continue;
        }
        const auto& full = f.natural(crossing_chart).equations;
        std::vector<model::Polynomial> eqs, dropped;
        std::vector<bool> kept(full.size(), true);
        bool indices_ok = true;
        for (auto& d : x.at("dropped_equations")) {
          const int k = d.get<int>();
          indices_ok = indices_ok && k >= 0 && k < static_cast<int>(kept.size());
          if (indices_ok) kept[k] = false;
        }
        for (size_t k = 0; k < kept.size(); ++k) (kept[k] ? eqs : dropped).push_back(full[k]);
        const newton::Certificate cert = certificate_from(x);
        const std::optional<Box> image = indices_ok ? proved_image(eqs, cert) : std::nullopt;
        if (!image || cert.fixed_variable < 0) {
          out.failures.push_back(where + ": a curve-crossing certificate does not hold");
          continue;
        }
        if (!encloses(box_from(x.at("image")), *image))
          out.failures.push_back(where + ": a curve crossing's stored Newton image does not contain the one its box and preconditioner give");
        if (std::any_of(dropped.begin(), dropped.end(), [&](auto& p) { return !zero_in(p.eval(cert.box)); }))
          out.failures.push_back(where + ": a dropped equation does not vanish on a crossing box");
        // The crossing must be in the member box it is listed for.
        const size_t member = x.at("member").get<size_t>();
        if (member >= c.at("members").size()) {
          out.failures.push_back(where + ": a curve crossing names a member the cluster does not have");
          continue;
        }
        const auto& m = c.at("members")[member];
        auto it = solutions.find({m.at(0).get<size_t>(), m.at(1).get<size_t>()});
        const auto crossing = carried([&] { return f.natural_to_output(crossing_chart, cert.box); });
        if (it == solutions.end() || !crossing || !boxes_touch(*crossing, it->second, periodic))
          out.failures.push_back(where + ": a curve crossing lies outside its member box");
      }
    }
  }
  for (auto& [key, i] : solutions)
    if (!owner.count(key)) {
      out.failures.push_back("solution box " + std::to_string(key.second) + " of sub-problem " + std::to_string(key.first) +
                             " is in no cluster: a root in it would not be counted");
      break;
    }
  // A duplicate is not counted, so the claim that it is one needs a proof: as the search's
  // verification made it, one certificate (re-derived here, deterministically) with no other
  // root in the hull of the first cluster's box and the duplicate's root box.
  for (size_t i : duplicates) {
    const json& b = clusters[i];
    const json& d = b.at("duplicate_of");
    const long a = d.is_number_integer() ? d.get<long>() : -1;
    bool proved = false;
    if (a >= 0 && a < static_cast<long>(clusters.size()) && a != static_cast<long>(i) &&
        clusters[a].at("status") == "certified" && !clusters[a].contains("duplicate_of")) {
      const json& first = clusters[a];
      const auto chart = first.at("chart").get<std::uint64_t>();
      try {
        const newton::Certificate cert = certificate_from(first.at("certificate"));
        const Box root = box_from(first.at("root")), other = box_from(b.at("root"));
        if (chart_exists(chart) && root.size() == outputs && other.size() == outputs) {
          const auto& sys = f.natural(chart);
          const auto mapped = carried([&] { return f.output_to_natural(chart, unwrapped(other, root, angles)); });
          if (mapped && mapped->size() == cert.box.size()) {
            const newton::Certificate both =
                newton::certify_root(sys.equations, linkbox::hull(cert.box, *mapped), sys.domain);
            proved = both.status == newton::Status::certified && both.unique_in_hull;
          }
        }
      } catch (const nlohmann::json::exception&) {  // malformed: nothing proved
      }
    }
    if (!proved)
      out.failures.push_back("cluster " + std::to_string(i) +
                             ": marked the duplicate of another cluster, but one root for both is not proved");
  }
  // "exactly N" needs every cluster settled: each certified one (duplicates too) proved alone
  // in its hull, no curve or unresolved cluster, the search complete.
  if (j.value("headline", std::string()).rfind("exactly", 0) == 0) {
    if (!j.value("complete", false)) out.failures.push_back("the headline states an exact count of an incomplete search");
    for (size_t i = 0; i < clusters.size(); ++i) {
      const std::string status = clusters[i].at("status");
      const bool map_proved = std::find(proved_maps.begin(), proved_maps.end(), i) != proved_maps.end();
      const bool settled = status == "empty" || status == "infeasible" || map_proved ||
                           (status == "certified" && clusters[i].at("certificate").value("unique_in_hull", false));
      if (!settled)
        out.failures.push_back("cluster " + std::to_string(i) + ": the headline states an exact count, but this cluster is " +
                               (status == "certified" ? "not proved to hold only its root" : status));
    }
  }
  for (size_t a = 0; a < proved_map_data.size(); ++a)
    for (size_t b = a + 1; b < proved_map_data.size(); ++b)
      if (!maps_apart(f, proved_map_data[a], proved_map_data[b]))
        out.failures.push_back("clusters " + std::to_string(proved_maps[a]) + " and " + std::to_string(proved_maps[b]) +
                               ": proved maps whose arcs may meet");
  if (j.contains("verification") && j.at("verification").contains("map")) {
    const json& m = j.at("verification").at("map");
    if (m.value("closed_curves", -1) != closed_curves || m.value("open_arcs", -1) != open_arcs)
      out.failures.push_back("the map's counts of closed curves and open arcs are not those its proved clusters give");
  }
  if (certified != j.at("certified_roots").get<int>())
    out.failures.push_back("certified_roots says " + std::to_string(j.at("certified_roots").get<int>()) + " but " +
                           std::to_string(certified) + " distinct certified clusters are listed");
  return out;
}

}  // namespace linkbox::verify
