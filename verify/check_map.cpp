#include "verify/check_map.hpp"

#include "verify/curve_map_json.hpp"
#include "verify/subsystem.hpp"
#include "verify/symmetric_map.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <map>
#include <memory>
#include <set>

namespace linkbox::verify {

namespace {

using Key = std::pair<size_t, std::vector<std::pair<double, double>>>;  // (member, piece)

Key key_of(size_t member, const Box& piece) {
  Key k{member, {}};
  for (auto& x : piece) k.second.emplace_back(x.lower(), x.upper());
  return k;
}

// The arcs speak of every natural equation, each once: n - 1 of them, or more through a
// coordinate subspace that the system has.
bool equations_fit(const CurveMap& m, ArcSystems& systems, size_t equations, size_t unknowns, bool links) {
  if (m.equations.size() != equations || links) return false;
  for (size_t k = 0; k < equations; ++k)
    if (m.equations[k] != static_cast<int>(k)) return false;
  if (m.subspace_variable < 0) return equations + 1 == unknowns;
  const auto& s = systems.subspace(m.charts[0]);
  return s && s->variable == m.subspace_variable;
}

// Re-proves the arcs (their image and ends recomputed) and walks every member's pieces.
void reprove(const formulate::Formulation& f, const std::vector<Box>& members, ArcSystems& systems, CurveMap& m,
             MapCheck& out) {
  std::map<Key, size_t> arc_at;
  for (size_t a = 0; a < m.arcs.size(); ++a) arc_at.emplace(key_of(m.arcs[a].member, m.arcs[a].piece), a);
  std::set<Key> unresolved;
  for (auto& [member, piece] : m.unresolved) unresolved.insert(key_of(member, piece));
  std::vector<bool> visited(m.arcs.size(), false);
  for (size_t k = 0; k < members.size(); ++k) {
    const std::uint64_t chart = m.charts[k];
    const auto& sys = f.natural(chart);
    const auto& exclusion = systems.for_exclusion(chart, m.subspace_variable);
    Box natural;
    try {
      natural = f.output_to_natural(chart, members[k]);
    } catch (const std::exception&) {
      out.failures.push_back("a member does not fit its chart");
      return;
    }
    auto is_arc = [&](const Box& piece) {
      auto it = arc_at.find(key_of(k, piece));
      if (it == arc_at.end()) return false;
      MapArc& a = m.arcs[it->second];
      const bool fits = a.chart == chart && contains(a.arc.box, piece) &&
                        (sys.domain.empty() || contains(sys.domain, a.arc.box));
      if (!systems.reprove(a, m.subspace_variable) || !fits)
        out.failures.push_back("an arc certificate does not hold on its piece");
      visited[it->second] = true;
      ++out.arcs;
      return true;
    };
    auto is_empty = [&](const Box& piece) { return piece_empty(sys.equations, exclusion, piece); };
    auto near = [&](const Box& piece) { return near_singular(m.singular_points, chart, piece); };
    walk_pieces(natural, near, is_arc, is_empty, [&](const Box& piece, PieceKind kind) {
      if (kind == PieceKind::unresolved && !unresolved.count(key_of(k, piece)))
        out.failures.push_back("a piece with neither an arc nor a proof of emptiness is not listed as unresolved");
    });
  }
  if (std::find(visited.begin(), visited.end(), false) != visited.end())
    out.failures.push_back("an arc lies on no piece of its member");
}

std::vector<std::pair<std::vector<size_t>, bool>> shape(const std::vector<MapComponent>& cs) {
  std::vector<std::pair<std::vector<size_t>, bool>> s;
  for (auto& c : cs) {
    auto arcs = c.arcs;
    std::sort(arcs.begin(), arcs.end());
    s.emplace_back(std::move(arcs), c.closed);
  }
  std::sort(s.begin(), s.end());
  return s;
}

bool same_arcs(const CurveMap& a, const CurveMap& b) {
  if (a.arcs.size() != b.arcs.size()) return false;
  for (size_t i = 0; i < a.arcs.size(); ++i) {
    const MapArc &x = a.arcs[i], &y = b.arcs[i];
    if (key_of(x.member, x.piece) != key_of(y.member, y.piece) || key_of(0, x.arc.box) != key_of(0, y.arc.box) ||
        x.arc.parameter != y.arc.parameter)
      return false;
  }
  return true;
}

// The stated kinds and branch counts are the recomputed ones.
bool same_singular(const std::vector<SingularPoint>& a, const std::vector<SingularPoint>& b) {
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); ++k)
    if (a[k].kind != b[k].kind || a[k].branches != b[k].branches) return false;
  return true;
}

// A map through the loop's symmetry (verify/symmetric_map.hpp) is recomputed whole from the
// members: every arc, exclusion and join proved anew. The file's arcs must be those.
void check_symmetric(const formulate::Formulation& f, const std::vector<Box>& members, CurveMap& m, MapCheck& out) {
  const auto loop = SymmetricLoop::of(f);
  const auto again = loop ? map_symmetric(*loop, members) : std::nullopt;
  if (!again || !same_arcs(*again, m)) {
    out.failures.push_back("its arcs are not those that the loop's symmetry proves");
    return;
  }
  out.arcs = static_cast<int>(again->arcs.size());
  if (shape(again->components) != shape(m.components) || again->proved != m.proved)
    out.failures.push_back("the map's components or its proof are not what its arcs give");
  out.proved = out.failures.empty() && again->proved;
  for (auto& c : again->components) ++(c.closed ? out.closed : out.open);
  out.map = *again;
}

}  // namespace

bool symmetric_empty(const formulate::Formulation& f, const std::vector<Box>& members) {
  const auto loop = SymmetricLoop::of(f);
  if (!loop || members.empty()) return false;
  for (const Box& m : members)
    if (max_width(m) > kSymmetricMember) return false;
  const auto map = map_symmetric(*loop, members);
  return map && map->arcs.empty() && map->unresolved.empty();
}

MapCheck check_map(const nlohmann::json& j, const formulate::Formulation& f, const std::vector<Box>& members,
                   const std::function<bool(std::uint64_t)>& chart_exists) {
  MapCheck out;
  CurveMap m;
  try {
    m = map_from(j);
  } catch (const std::exception& e) {
    out.failures.push_back(std::string("a malformed map: ") + e.what());
    return out;
  }
  const CurveMap stated = m;
  const bool sizes_fit = m.charts.size() == members.size() &&
                         std::all_of(m.arcs.begin(), m.arcs.end(), [&](auto& a) { return a.member < members.size(); }) &&
                         std::all_of(m.unresolved.begin(), m.unresolved.end(), [&](auto& u) { return u.first < members.size(); }) &&
                         std::all_of(m.charts.begin(), m.charts.end(), chart_exists);
  if (!sizes_fit || members.empty()) {
    out.failures.push_back("the map's members or charts do not match the cluster's");
    return out;
  }
  if (m.equations.empty()) {  // the symmetric loop's maps speak of no natural equations
    if (!m.singular_points.empty()) out.failures.push_back("a symmetric loop's map states singular points");
    check_symmetric(f, members, m, out);
    return out;
  }
  const auto& sys = f.natural(m.charts[0]);
  ArcSystems systems(f);
  if (!equations_fit(m, systems, sys.equations.size(), sys.unknowns.size(), !sys.links.empty())) {
    out.failures.push_back("the map's equations are not the natural system's n - 1, nor redundant through its subspace");
    return out;
  }
  for (auto& p : m.singular_points) {
    const bool fits = chart_exists(p.chart) && m.subspace_variable < 0 &&
                      f.natural(p.chart).equations.size() + 1 == f.natural(p.chart).unknowns.size();
    if (!fits || !reprove_singular_point(f.natural(p.chart).equations, p))
      out.failures.push_back("a singular point's certificate does not hold");
  }
  if (!out.failures.empty()) return out;
  reprove(f, members, systems, m, out);
  if (!out.failures.empty()) return out;
  join_arcs(f, members, m);
  if (shape(m.components) != shape(stated.components) || m.proved != stated.proved ||
      !same_singular(m.singular_points, stated.singular_points))
    out.failures.push_back("the map's components or its proof are not what its arcs give");
  out.proved = out.failures.empty() && m.proved;
  for (auto& c : m.components) ++(c.singular_ends ? out.branches : c.closed ? out.closed : out.open);
  out.singular = static_cast<int>(m.singular_points.size());
  out.map = std::move(m);
  return out;
}

}  // namespace linkbox::verify
