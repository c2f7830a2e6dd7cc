#include "verify/check.hpp"

#include "newton/certify.hpp"
#include "verify/check_arguments.hpp"
#include "verify/check_claims.hpp"
#include "verify/check_map.hpp"
#include "verify/check_proofs.hpp"
#include "verify/check_json.hpp"
#include "verify/cluster.hpp"
#include "verify/exact_point.hpp"
#include "verify/isolated.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

namespace linkbox::verify {

using nlohmann::json;

namespace {

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

// One cluster of the result as its checks read it.
struct Entry {
  size_t index;
  const json& c;
  std::string where;  // "cluster i", how its failures begin
  std::uint64_t chart;
  Box hull;
};

// check_certificates' steps, in the order they run, and what the clusters establish for the
// checks of the whole result (owners of the solution boxes, duplicates, proved maps, counts).
class Checker {
 public:
  Checker(const json& j, const formulate::Formulation& f)
      : j_(j), f_(f), outputs_(f.output_names().size()), angles_(f.outputs_are_angles()), periodic_(outputs_, angles_) {}

  CheckOutcome run() {
    // A result for other variables is not this case's (the names are all a result states).
    if (j_.contains("variables") && j_.at("variables") != f_.output_names())
      out_.failures.push_back("the result's variables are not the case's");
    index_solutions();
    clusters_ = &j_.at("clusters");
    for (size_t i = 0; i < clusters_->size(); ++i) check_cluster(i);
    check_every_box_clustered();
    check_duplicates();
    check_exact_headline();
    check_maps_apart();
    check_map_counts();
    if (certified_ != j_.at("certified_roots").get<int>())
      out_.failures.push_back("certified_roots says " + std::to_string(j_.at("certified_roots").get<int>()) + " but " +
                              std::to_string(certified_) + " distinct certified clusters are listed");
    check_claims(j_, f_, reproved_clusters(), out_.failures);
    return out_;
  }

 private:
  // Charts are masks of half-turn shifts of the angle outputs; other formulations have one.
  bool chart_exists(std::uint64_t chart) const { return angles_ ? outputs_ >= 64 || chart >> outputs_ == 0 : chart == 0; }

  // Solution boxes by (sub-problem, index within it), to check that hulls cover members.
  void index_solutions() {
    std::map<size_t, size_t> seen;
    for (auto& s : j_.at("solutions")) {
      const size_t sub = s.at("subproblem");
      solutions_[{sub, seen[sub]++}] = box_from(s.at("box"));
    }
  }

  void check_cluster(size_t i) {
    const json& c = (*clusters_)[i];
    const std::string where = "cluster " + std::to_string(i);
    const std::string status = c.at("status");
    const auto chart = c.at("chart").get<std::uint64_t>();
    const Entry k{i, c, where, chart, box_from(c.at("hull"))};
    check_members(k);
    if (k.hull.size() != outputs_ || !chart_exists(chart)) {
      out_.failures.push_back(where + ": its hull or chart does not fit the case's " + std::to_string(outputs_) +
                              " variables");
      return;
    }
    const auto& sys = f_.natural(chart);
    if (status == "certified" && c.contains("argument")) {
      check_argument(k, sys);
    } else if (status == "certified") {
      check_certified(k, sys);
    } else if (status == "empty") {
      check_empty(k, sys);
    } else if (status == "infeasible") {
      check_infeasible(k, sys);
    } else if (status == "unverified" && c.contains("subsystem") && c.at("certificate").at("status") == "certified") {
      check_subsystem(k, sys);
    } else if (status == "curve" && !sys.links.empty()) {
      out_.failures.push_back(where + ": called a curve in a system with links (curves are certified without them)");
    } else if (status == "curve") {
      if (c.contains("map")) check_curve_map(k);
      std::set<size_t> crossed;
      for (auto& x : c.at("crossings"))
        if (x.at("status") == "certified" && check_crossing(k, x)) crossed.insert(x.at("member").get<size_t>());
      // What verification calls a curve: a map (proved or not) that re-proves, or certified
      // crossings in at least half of its boxes.
      if (!reproved_maps_.count(i) && 2 * crossed.size() < c.at("members").size())
        out_.failures.push_back(where + ": called a curve, but it has no map and certified crossings cover fewer than half of its boxes");
    } else if (status != "unverified") {
      out_.failures.push_back(where + ": unknown status '" + status + "'");
    }
  }

  // Every solution box must be a member of exactly one cluster: a box left out of every
  // cluster (or a cluster left out) could hold a root the count never sees.
  void check_members(const Entry& k) {
    for (auto& m : k.c.at("members")) {
      const std::pair<size_t, size_t> key{m.at(0).get<size_t>(), m.at(1).get<size_t>()};
      auto it = solutions_.find(key);
      if (it == solutions_.end() || !covers(k.hull, it->second, angles_))
        out_.failures.push_back(k.where + ": its hull does not cover its member solution boxes");
      else if (auto [at, fresh] = owner_.emplace(key, k.index); !fresh)
        out_.failures.push_back(k.where + ": lists a solution box that cluster " + std::to_string(at->second) +
                                " lists too");
    }
  }

  void check_certified(const Entry& k, const formulate::NaturalSystem& sys) {
    ++out_.checked;
    const json& cj = k.c.at("certificate");
    const newton::Certificate cert = certificate_from(cj);
    const std::optional<Box> image = proved_image(sys, cert);
    if (!image) {
      out_.failures.push_back(k.where + ": the Newton test does not hold on the stored box and preconditioner");
      return;
    }
    // The stored image is the result's tightest enclosure of the root: it must hold the
    // image the box and preconditioner give (which holds the root).
    if (!encloses(box_from(cj.at("image")), *image))
      out_.failures.push_back(k.where + ": the stored Newton image does not contain the one its box and preconditioner give");
    check_root(k, sys, cert, *image);
  }

  // What a certified cluster claims of its root, on the certified box (or at its exact root):
  // the reported root encloses it, the inequalities hold, no other root is in the hull if claimed.
  void check_root(const Entry& k, const formulate::NaturalSystem& sys, const newton::Certificate& cert,
                  const Box& image) {
    const json& cj = k.c.at("certificate");
    const auto root = carried([&] { return f_.natural_to_output(k.chart, cert.box); });
    if (!root || !encloses(box_from(k.c.at("root")), *root))
      out_.failures.push_back(k.where + ": the reported root box does not enclose the certified box");
    const std::vector<std::string> exact = exact_root(k, sys, image);
    for (auto& q : sys.inequalities)
      if (side_of_root(q, cert.box, exact) != model::Side::inside)
        out_.failures.push_back(k.where + ": the certified root is not proved to satisfy \"" + q.name + "\"");
    if (!sys.domain.empty() && cj.value("root_in_domain", false) && !encloses(sys.domain, image) &&
        !(exact.size() && rationals_in(exact, sys.domain)))
      out_.failures.push_back(k.where + ": root claimed in the domain but neither its image nor exact root is");
    // "No other root in the cluster" is what makes a count exact: re-proved, not read.
    if (cj.value("unique_in_hull", false) && !k.c.contains("argument")) {
      const auto start = carried([&] { return f_.output_to_natural(k.chart, k.hull); });
      if (!start || !unique_over(sys, *start, cert))
        out_.failures.push_back(k.where + ": no other root in its hull is claimed but not proved");
    }
    if (!k.c.contains("duplicate_of")) ++certified_;
    else duplicates_.push_back(k.index);
  }

  // The cluster's exact root, when it states one that holds (a failure when it does not).
  std::vector<std::string> exact_root(const Entry& k, const formulate::NaturalSystem& sys, const std::optional<Box>& image) {
    const auto p = k.c.value("exact_root", std::vector<std::string>{});
    if (p.empty() || (image && sys.links.empty() && exact_root_in(sys.equations, p, *image))) return p;
    out_.failures.push_back(k.where + ": its exact root is not a root in its certified image");
    return {};
  }

  // Certified by an argument for the equations its square subsystem leaves out
  // (verify/check_arguments.hpp).
  void check_argument(const Entry& k, const formulate::NaturalSystem& sys) {
    ++out_.checked;
    const std::string argument = k.c.at("argument");
    const auto start = carried([&] { return f_.output_to_natural(k.chart, k.hull); });
    std::optional<Box> image;
    if (start && argument == "exact root") image = recheck_exact_root(sys, k.c, *start);
    if (start && argument == "coupled loops") image = recheck_coupled_loops(f_, k.chart, k.c, *start);
    if (!image) {
      out_.failures.push_back(k.where + ": the proof of its root " +
                              (argument == "coupled loops" ? "through its loops" : "by " + argument) + " does not hold");
      return;
    }
    check_root(k, sys, certificate_from(k.c.at("certificate")), *image);
  }

  void check_empty(const Entry& k, const formulate::NaturalSystem& sys) {
    ++out_.checked;
    const json& c = k.c;
    if (const auto b = members_of(k); b.size() == c.at("members").size() && symmetric_empty(f_, b)) return;
    newton::Certificate cert = certificate_from(c.at("certificate"));
    std::vector<model::Polynomial> eqs;
    bool holds = cert.box.size() == sys.unknowns.size() && equations_named(c, "subsystem", sys.equations, eqs);
    if (holds && c.contains("excluding_equation")) {
      // Proved by evaluation: that equation's range over the box misses 0.
      const int e = c.at("excluding_equation");
      holds = excludes(sys, e, cert.box);
    } else if (holds) {
      holds = newton::recheck_exclusion(eqs, cert.box, cert.preconditioner, cert.method);
    }
    if (!holds)
      out_.failures.push_back(k.where + ": the proof that this cluster holds no root does not hold");
    else if (const auto start = carried([&] { return f_.output_to_natural(k.chart, k.hull); });
             !start || !encloses(cert.box, *start))
      out_.failures.push_back(k.where + ": the box proved empty does not cover the cluster");
  }

  // No root where the inequalities hold: one fails on the certified box of the cluster's
  // only root, or on a box that covers the cluster.
  void check_infeasible(const Entry& k, const formulate::NaturalSystem& sys) {
    ++out_.checked;
    const json& c = k.c;
    const newton::Certificate cert = certificate_from(c.at("certificate"));
    const bool certified = c.at("certificate").at("status") == "certified";
    const auto exact = certified ? exact_root(k, sys, proved_image(sys, cert)) : std::vector<std::string>{};
    bool holds = cert.box.size() == sys.unknowns.size() &&
                 std::any_of(sys.inequalities.begin(), sys.inequalities.end(),
                             [&](auto& q) { return side_of_root(q, cert.box, exact) == model::Side::outside; });
    const auto start = carried([&] { return f_.output_to_natural(k.chart, k.hull); });
    if (certified)
      holds = holds && c.at("certificate").value("unique_in_hull", false) &&
              (sys.links.empty() ? newton::recheck(sys.equations, cert) : proved_image(sys, cert).has_value()) &&
              start && unique_over(sys, *start, cert);
    else
      holds = holds && start && encloses(cert.box, *start);
    if (!holds)
      out_.failures.push_back(k.where + ": the proof that this cluster holds no root satisfying the inequalities does not hold");
  }

  // An overdetermined system's square subsystem: its unique root is what the reason speaks
  // of, and the other equations contain 0 on its box.
  void check_subsystem(const Entry& k, const formulate::NaturalSystem& sys) {
    ++out_.checked;
    std::vector<model::Polynomial> eqs;
    const newton::Certificate cert = certificate_from(k.c.at("certificate"));
    if (!equations_named(k.c, "subsystem", sys.equations, eqs) || !newton::recheck(eqs, cert)) {
      out_.failures.push_back(k.where + ": the certificate of its square subsystem does not hold");
      return;
    }
    for (size_t e = 0; e < sys.equations.size() + sys.links.size(); ++e)
      if (excludes(sys, static_cast<int>(e), cert.box)) {
        out_.failures.push_back(k.where + ": natural equation " + std::to_string(e) + " misses 0 on the subsystem's box");
        break;
      }
  }

  // The cluster's members, unwrapped towards the first as verification unwrapped them.
  std::vector<Box> members_of(const Entry& k) const {
    std::vector<Box> boxes;
    for (auto& m : k.c.at("members")) {
      auto it = solutions_.find({m.at(0).get<size_t>(), m.at(1).get<size_t>()});
      if (it != solutions_.end()) boxes.push_back(boxes.empty() ? it->second : unwrap(it->second, boxes[0], angles_));
    }
    return boxes;
  }

  void check_curve_map(const Entry& k) {
    const std::vector<Box> boxes = members_of(k);
    const auto exists = [&](std::uint64_t chart) { return chart_exists(chart); };
    MapCheck mc = boxes.size() == k.c.at("members").size() ? check_map(k.c.at("map"), f_, boxes, exists)
                                                            : MapCheck{{"members missing"}, false, 0, 0, 0, 0, 0, {}};
    out_.checked += mc.arcs;
    for (auto& why : mc.failures) out_.failures.push_back(k.where + ": its map: " + why);
    if (mc.failures.empty()) reproved_maps_[k.index] = mc.map;
    if (mc.proved) {
      proved_map_data_.push_back(std::move(mc.map));  // as re-proved, never as written
      proved_maps_.push_back(k.index);
      closed_curves_ += mc.closed, open_arcs_ += mc.open, branches_ += mc.branches, singular_points_ += mc.singular;
    }
  }

  // Whether the crossing holds, in full.
  bool check_crossing(const Entry& k, const json& x) {
    ++out_.checked;
    // Each crossing in its own chart: a curve around a whole turn fits no single one.
    const std::uint64_t crossing_chart = x.value("chart", k.chart);
    if (!chart_exists(crossing_chart)) {
      out_.failures.push_back(k.where + ": a curve crossing names a chart the case does not have");
      return false;
    }
    if (!f_.natural(crossing_chart).links.empty()) {
      out_.failures.push_back(k.where + ": a curve crossing in a system with links (curves are certified without them)");
      return false;
    }
    const auto& full = f_.natural(crossing_chart).equations;
    std::vector<model::Polynomial> eqs, dropped;
    std::vector<bool> kept(full.size(), true);
    bool indices_ok = true;
    for (auto& d : x.at("dropped_equations")) {
      const int e = d.get<int>();
      indices_ok = indices_ok && e >= 0 && e < static_cast<int>(kept.size());
      if (indices_ok) kept[e] = false;
    }
    for (size_t e = 0; e < kept.size(); ++e) (kept[e] ? eqs : dropped).push_back(full[e]);
    const newton::Certificate cert = certificate_from(x);
    const std::optional<Box> image = indices_ok ? proved_image(eqs, cert) : std::nullopt;
    if (!image || cert.fixed_variable < 0) {
      out_.failures.push_back(k.where + ": a curve-crossing certificate does not hold");
      return false;
    }
    const size_t failed = out_.failures.size();
    if (!encloses(box_from(x.at("image")), *image))
      out_.failures.push_back(k.where + ": a curve crossing's stored Newton image does not contain the one its box and preconditioner give");
    if (std::any_of(dropped.begin(), dropped.end(), [&](auto& p) { return !zero_in(p.eval(cert.box)); }))
      out_.failures.push_back(k.where + ": a dropped equation does not vanish on a crossing box");
    // The crossing must be in the member box it is listed for.
    const size_t member = x.at("member").get<size_t>();
    if (member >= k.c.at("members").size()) {
      out_.failures.push_back(k.where + ": a curve crossing names a member the cluster does not have");
      return false;
    }
    const auto& m = k.c.at("members")[member];
    auto it = solutions_.find({m.at(0).get<size_t>(), m.at(1).get<size_t>()});
    const auto crossing = carried([&] { return f_.natural_to_output(crossing_chart, cert.box); });
    if (it == solutions_.end() || !crossing || !boxes_touch(*crossing, it->second, periodic_))
      out_.failures.push_back(k.where + ": a curve crossing lies outside its member box");
    return out_.failures.size() == failed;
  }

  // The clusters as the checks above leave them: each field the headline and counts need is
  // either re-proved above (a failure was recorded otherwise) or, like `reason`, descriptive.
  std::vector<ClusterReport> reproved_clusters() const {
    std::vector<ClusterReport> out;
    for (size_t i = 0; i < clusters_->size(); ++i) {
      const json& c = (*clusters_)[i];
      ClusterReport r;
      const std::string status = c.at("status");
      r.status = status == "certified"    ? ClusterStatus::certified
                 : status == "curve"      ? ClusterStatus::curve
                 : status == "empty"      ? ClusterStatus::empty
                 : status == "infeasible" ? ClusterStatus::infeasible
                                          : ClusterStatus::unverified;
      r.reason = c.value("reason", "");
      r.boxes.resize(c.at("members").size());
      if (r.status == ClusterStatus::certified) {
        r.certificate.unique_in_hull = c.at("certificate").value("unique_in_hull", false);
        r.root = box_from(c.at("root"));
        const json& d = c.value("duplicate_of", json(-1));
        r.duplicate_of = d.is_number_integer() ? d.get<int>() : -1;
      }
      if (auto it = reproved_maps_.find(i); it != reproved_maps_.end()) r.map = it->second;
      out.push_back(std::move(r));
    }
    return out;
  }

  void check_every_box_clustered() {
    for (auto& [key, i] : solutions_)
      if (!owner_.count(key)) {
        out_.failures.push_back("solution box " + std::to_string(key.second) + " of sub-problem " +
                                std::to_string(key.first) + " is in no cluster: a root in it would not be counted");
        break;
      }
  }

  // A duplicate is not counted, so the claim that it is one needs a proof: as the search's
  // verification made it, one certificate (re-derived here, deterministically) with no other
  // root in the hull of the first cluster's box and the duplicate's root box.
  void check_duplicates() {
    for (size_t i : duplicates_)
      if (!duplicate_proved(i))
        out_.failures.push_back("cluster " + std::to_string(i) +
                                ": marked the duplicate of another cluster, but one root for both is not proved");
  }

  bool duplicate_proved(size_t i) const {
    const json& clusters = *clusters_;
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
        if (chart_exists(chart) && root.size() == outputs_ && other.size() == outputs_) {
          const auto& sys = f_.natural(chart);
          const auto mapped = carried([&] { return f_.output_to_natural(chart, unwrap(other, root, angles_)); });
          if (mapped && mapped->size() == cert.box.size()) {
            const newton::Certificate both = certify_natural(sys, linkbox::hull(cert.box, *mapped));
            proved = both.status == newton::Status::certified && both.unique_in_hull;
          }
        }
      } catch (const nlohmann::json::exception&) {  // malformed: nothing proved
      }
    }
    return proved;
  }

  // "exactly N" needs every cluster settled: each certified one (duplicates too) proved alone
  // in its hull, no curve or unresolved cluster, the search complete.
  void check_exact_headline() {
    if (j_.value("headline", std::string()).rfind("exactly", 0) != 0) return;
    if (!j_.value("complete", false)) out_.failures.push_back("the headline states an exact count of an incomplete search");
    const json& clusters = *clusters_;
    for (size_t i = 0; i < clusters.size(); ++i) {
      const std::string status = clusters[i].at("status");
      const bool map_proved = std::find(proved_maps_.begin(), proved_maps_.end(), i) != proved_maps_.end();
      const bool settled = status == "empty" || status == "infeasible" || map_proved ||
                           (status == "certified" && clusters[i].at("certificate").value("unique_in_hull", false));
      if (!settled)
        out_.failures.push_back("cluster " + std::to_string(i) + ": the headline states an exact count, but this cluster is " +
                                (status == "certified" ? "not proved to hold only its root" : status));
    }
  }

  void check_maps_apart() {
    for (size_t a = 0; a < proved_map_data_.size(); ++a)
      for (size_t b = a + 1; b < proved_map_data_.size(); ++b)
        if (!maps_apart(f_, proved_map_data_[a], proved_map_data_[b]))
          out_.failures.push_back("clusters " + std::to_string(proved_maps_[a]) + " and " +
                                  std::to_string(proved_maps_[b]) + ": proved maps whose arcs may meet");
  }

  void check_map_counts() {
    if (!j_.contains("verification") || !j_.at("verification").contains("map")) return;
    const json& m = j_.at("verification").at("map");
    if (m.value("closed_curves", -1) != closed_curves_ || m.value("open_arcs", -1) != open_arcs_ ||
        m.value("branches", 0) != branches_ || m.value("singular_points", 0) != singular_points_)
      out_.failures.push_back("the map's counts of components and singular points are not those its proved clusters give");
  }

  const json& j_;
  const formulate::Formulation& f_;
  const size_t outputs_;
  const bool angles_;
  const std::vector<bool> periodic_;
  const json* clusters_ = nullptr;
  std::map<std::pair<size_t, size_t>, Box> solutions_;
  std::map<std::pair<size_t, size_t>, size_t> owner_;  // the cluster listing each solution box
  std::vector<size_t> duplicates_;       // certified clusters marked duplicate_of another
  std::vector<size_t> proved_maps_;      // curve clusters whose map re-proves as proved
  std::vector<CurveMap> proved_map_data_;
  std::map<size_t, CurveMap> reproved_maps_;  // curve clusters whose map re-proves, by index
  int certified_ = 0, closed_curves_ = 0, open_arcs_ = 0, branches_ = 0, singular_points_ = 0;
  CheckOutcome out_;
};

}  // namespace

CheckOutcome check_certificates(const json& j, const formulate::Formulation& f, const std::string& case_sha256) {
  if (!case_sha256.empty() && j.value("case_sha256", std::string()) != case_sha256)
    return {0, {"not the case that was solved: the case file's SHA-256 is " + case_sha256 + ", the result's " +
                j.value("case_sha256", std::string("missing"))}};
  return Checker(j, f).run();
}

}  // namespace linkbox::verify
