#include "verify/check.hpp"

#include "newton/certify.hpp"
#include "verify/cluster.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <map>

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
  c.method = j.at("method") == "krawczyk" ? newton::Method::krawczyk : newton::Method::hansen_sengupta;
  c.box = box_from(j.at("box"));
  const json& m = j.at("preconditioner");
  c.preconditioner.resize(m.size(), m.empty() ? 0 : m[0].size());
  for (size_t r = 0; r < m.size(); ++r)
    for (size_t k = 0; k < m[r].size(); ++k) c.preconditioner(r, k) = m[r][k].get<double>();
  c.fixed_variable = j.value("fixed_variable", -1);
  return c;
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
  // Solution boxes by (sub-problem, index within it), to check that hulls cover members.
  std::map<std::pair<size_t, size_t>, Box> solutions;
  std::map<size_t, size_t> seen;
  for (auto& s : j.at("solutions")) {
    const size_t sub = s.at("subproblem");
    solutions[{sub, seen[sub]++}] = box_from(s.at("box"));
  }
  int certified = 0;
  const std::vector<bool> periodic(f.output_names().size(), f.outputs_are_angles());
  const auto& clusters = j.at("clusters");
  for (size_t i = 0; i < clusters.size(); ++i) {
    const json& c = clusters[i];
    const std::string where = "cluster " + std::to_string(i);
    const std::string status = c.at("status");
    const auto chart = c.at("chart").get<std::uint64_t>();
    const auto& sys = f.natural(chart);
    const Box hull = box_from(c.at("hull"));
    for (auto& m : c.at("members")) {
      auto it = solutions.find({m.at(0).get<size_t>(), m.at(1).get<size_t>()});
      if (it == solutions.end() || !covers(hull, it->second, f.outputs_are_angles()))
        out.failures.push_back(where + ": its hull does not cover its member solution boxes");
    }
    if (status == "certified") {
      ++out.checked;
      newton::Certificate cert = certificate_from(c.at("certificate"));
      if (!newton::recheck(sys.equations, cert)) {
        out.failures.push_back(where + ": the Newton test does not hold on the stored box and preconditioner");
        continue;
      }
      // The reported root must enclose what the certified box maps to.
      if (!contains(box_from(c.at("root")), f.natural_to_output(chart, cert.box)))
        out.failures.push_back(where + ": the reported root box does not enclose the certified box");
      if (!sys.domain.empty() && c.at("certificate").value("root_in_domain", false)) {
        auto image = box_from(c.at("certificate").at("image"));
        if (!contains(sys.domain, image)) out.failures.push_back(where + ": root claimed in the domain but its image is not");
      }
      if (!c.contains("duplicate_of")) ++certified;
    } else if (status == "empty") {
      ++out.checked;
      const json& cj = c.at("certificate");
      newton::Certificate cert = certificate_from(cj);
      std::vector<model::Polynomial> eqs;
      bool holds = equations_named(c, "subsystem", sys.equations, eqs);
      if (holds && c.contains("excluding_equation")) {
        // Proved by evaluation: that equation's range over the box misses 0.
        const int k = c.at("excluding_equation");
        holds = k >= 0 && k < static_cast<int>(sys.equations.size()) && !zero_in(sys.equations[k].eval(cert.box));
      } else if (holds) {
        holds = newton::recheck_exclusion(eqs, cert.box, cert.preconditioner, cert.method);
      }
      if (!holds)
        out.failures.push_back(where + ": the proof that this cluster holds no root does not hold");
      else if (!contains(cert.box, f.output_to_natural(chart, box_from(c.at("hull")))))
        out.failures.push_back(where + ": the box proved empty does not cover the cluster");
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
      for (auto& x : c.at("crossings")) {
        if (x.at("status") != "certified") continue;
        ++out.checked;
        // Each crossing in its own chart: a curve around a whole turn fits no single one.
        const std::uint64_t crossing_chart = x.value("chart", chart);
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
        if (!indices_ok || !newton::recheck(eqs, cert)) {
          out.failures.push_back(where + ": a curve-crossing certificate does not hold");
          continue;
        }
        if (std::any_of(dropped.begin(), dropped.end(), [&](auto& p) { return !zero_in(p.eval(cert.box)); }))
          out.failures.push_back(where + ": a dropped equation does not vanish on a crossing box");
        // The crossing must be in the member box it is listed for.
        const auto& m = c.at("members").at(x.at("member").get<size_t>());
        auto it = solutions.find({m.at(0).get<size_t>(), m.at(1).get<size_t>()});
        if (it == solutions.end() ||
            !boxes_touch(f.natural_to_output(crossing_chart, cert.box), it->second, periodic))
          out.failures.push_back(where + ": a curve crossing lies outside its member box");
      }
    }
  }
  if (certified != j.at("certified_roots").get<int>())
    out.failures.push_back("certified_roots says " + std::to_string(j.at("certified_roots").get<int>()) + " but " +
                           std::to_string(certified) + " distinct certified clusters are listed");
  return out;
}

}  // namespace linkbox::verify
