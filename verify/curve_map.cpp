#include "verify/curve_map.hpp"

#include "verify/cluster.hpp"
#include "verify/exact_point.hpp"
#include "verify/subsystem.hpp"

#include <algorithm>
#include <map>
#include <memory>
#include <numeric>
#include <set>

namespace linkbox::verify {

namespace {

// Members whose pieces are left unresolved, beyond which a cluster is not mapped at all: its
// boxes do not follow a regular curve of the kept equations (a singular isolated root, a
// surface), and trying every piece of every member would only cost time.
bool too_many_unresolved(size_t unresolved_members, size_t done) {
  return done >= 8 && 2 * unresolved_members > done;
}

size_t find(std::vector<size_t>& parent, size_t a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

// An end's enclosure carried into another chart's natural unknowns (the same box when the
// charts agree); empty when it cannot be carried.
std::optional<Box> in_chart(const formulate::Formulation& f, const Box& end, std::uint64_t from, std::uint64_t to) {
  if (from == to) return end;
  try {
    return f.output_to_natural(to, f.natural_to_output(from, end));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

bool disjoint(const Box& a, const Box& b) { return a.size() != b.size() || !overlaps(a, b); }

// The singular point whose box U holds an arc's end, if any.
const SingularPoint* singular_holding(const formulate::Formulation& f, const std::vector<SingularPoint>& points, const Box& end,
                                std::uint64_t chart) {
  for (auto& p : points) {
    const auto e = in_chart(f, end, chart, p.chart);
    if (e && e->size() == p.normal.size() + 1 && contains(p.where(), *e)) return &p;
  }
  return nullptr;
}

// Whether end `side` of `a` lies on the boundary of the natural domain (empty: unbounded).
bool on_domain_boundary(const newton::Arc& a, int side, const Box& domain) {
  if (domain.empty()) return false;
  const Interval& t = a.box[a.parameter];
  const Interval& d = domain[a.parameter];
  return side == 0 ? t.lower() <= d.lower() : t.upper() >= d.upper();
}

std::string plural(size_t k, const char* one, const char* many) {
  return std::to_string(k) + " " + (k == 1 ? one : many);
}

}  // namespace

// "2 singular points (crossings at (1, 0, 1, 0) and (-1, 0, -1, 0), each exact and the only
// one in its box; 4 and 4 branches reach their boxes)".
std::string singular_words(const std::vector<SingularPoint>& points) {
  std::string where, ends;
  for (size_t k = 0; k < points.size(); ++k) {
    const char* join = k == 0 ? "" : k + 1 == points.size() ? " and " : ", ";
    std::string p;
    for (auto& x : points[k].point) p += (p.empty() ? "" : ", ") + x;
    where += join + std::string(to_string(points[k].kind)) + " at (" + p + ")";
    ends += join + std::to_string(points[k].branches);
  }
  return plural(points.size(), "singular point", "singular points") + " (" + where +
         (points.size() == 1 ? ", exact and the only one in its box; " : ", each exact and the only one in its box; ") +
         ends + " branches reach " + (points.size() == 1 ? "its box)" : "their boxes)");
}

void state_map(CurveMap& map) {
  size_t closed = 0, open = 0, branches = 0;
  for (auto& c : map.components) ++(c.singular_ends ? branches : c.closed ? closed : open);
  std::string what;
  if (closed) what = plural(closed, "closed curve", "closed curves");
  if (open) what += (what.empty() ? "" : " and ") + plural(open, "open arc", "open arcs") + " (ending on the domain's boundary)";
  if (branches) what += (what.empty() ? "" : " and ") + plural(branches, "branch", "branches") + " between singular points";
  if (what.empty()) what = "no arc";
  if (map.proved) {
    const std::string subspace = map.subspace_variable < 0 ? "" : " (each also an arc, on " + map.argument +
        " = 0, of the equations that do not vanish there)";
    map.statement = what + ", proved: " + plural(map.arcs.size(), "arc certificate", "arc certificates") + subspace +
                    ", " + (map.singular_points.empty() ? "no singular point" : singular_words(map.singular_points));
    return;
  }
  std::string why;
  if (!map.unresolved.empty())
    why += std::string(why.empty() ? "" : "; ") + plural(map.unresolved.size(), "piece", "pieces") +
           " where no arc was proved, in " + plural(map.singular_regions.size(), "region", "regions") +
           (map.inexact_coefficients ? " (possible singular points, which cannot be proved here: some coefficients "
                                       "have no exact value, e.g. pi or sqrt(2), and a singular point is proved in "
                                       "exact arithmetic)"
                                     : " (possible singular points)");
  if (map.undecided_ends) why += std::string(why.empty() ? "" : "; ") + plural(map.undecided_ends, "arc end", "arc ends") + " not placed";
  if (map.loose_ends) why += std::string(why.empty() ? "" : "; ") + plural(map.loose_ends, "arc end", "arc ends") + " not continued";
  map.statement = "arcs joined into " + plural(map.components.size(), "branch", "branches") + ", not proved: " + why;
}

namespace {

// Members tried whole before a cluster is mapped, and how many must hold an arc: a cluster
// whose boxes do not follow a regular curve of the kept equations (a singular isolated root,
// a curve only of the whole system) fails here at the cost of 16 arc tests, not a walk of
// every member's pieces.
constexpr size_t kSample = 16, kSampleNeeded = 12;

// The sample's arcs by member (failed tries too, so no member is tried twice whole); empty
// when too few hold.
template <class Prove>
std::map<size_t, std::optional<MapArc>> sample_arcs(const formulate::Formulation& f, const std::vector<Box>& members,
                                                    const std::vector<std::uint64_t>& charts, Prove&& prove) {
  const size_t tries = std::min(kSample, members.size());
  std::map<size_t, std::optional<MapArc>> sample;
  size_t passed = 0;
  for (size_t s = 0; s < tries; ++s) {
    const size_t k = s * members.size() / tries;
    try {
      auto a = prove(k, f.output_to_natural(charts[k], members[k]));
      passed += a.has_value();
      sample.emplace(k, std::move(a));
    } catch (const std::exception&) {
    }
  }
  if (passed * kSample < kSampleNeeded * tries) sample.clear();
  return sample;
}

// An arc through the piece: of n - 1 equations, or of a redundant system through its
// coordinate subspace (each choice of the surplus equation kept in turn).
std::optional<MapArc> prove_arc(const formulate::Formulation& f, ArcSystems& systems, int subspace_variable,
                                size_t member, std::uint64_t chart, const Box& piece,
                                const newton::NewtonOptions& options) {
  const Box& domain = f.natural(chart).domain;
  if (subspace_variable < 0) {
    newton::Arc a = newton::certify_arc(systems.kept(chart, {}), piece, domain, options);
    if (!a.certified) return std::nullopt;
    return MapArc{member, chart, piece, std::move(a), {}, {}};
  }
  const auto& s = systems.subspace(chart);
  if (!s || s->variable != subspace_variable) return std::nullopt;
  Box mid = piece;
  for (auto& x : mid) x = Interval(median(x));
  for (size_t v : keep_order(*s, mid)) {
    std::vector<int> dropped = dropped_for(*s, v);
    newton::Arc a = newton::certify_arc(systems.kept(chart, dropped), piece, domain, options);
    if (a.certified && spans_on_subspace(*s, a.box, a.parameter))
      return MapArc{member, chart, piece, std::move(a), {}, std::move(dropped)};
  }
  return std::nullopt;
}

// The unresolved pieces in output variables, grouped where they touch, as hulls.
std::vector<Box> regions(const formulate::Formulation& f, const CurveMap& map, bool angles) {
  std::vector<Box> pieces;
  std::vector<Box> out;
  try {
    for (auto& [member, piece] : map.unresolved) pieces.push_back(f.natural_to_output(map.charts[member], piece));
  } catch (const std::exception&) {
    return out;  // named only where they can be carried to the outputs
  }
  if (pieces.empty()) return out;
  for (auto& g : cluster_boxes(pieces, std::vector<bool>(pieces[0].size(), angles))) {
    Box h = pieces[g[0]];
    for (int i : g) h = hull(h, pieces[i]);
    out.push_back(h);
  }
  return out;
}

}  // namespace

const std::shared_ptr<const model::CompiledSystem>& ArcSystems::kept(std::uint64_t chart,
                                                                    const std::vector<int>& dropped) {
  auto& eqs = kept_[{chart, dropped}];
  if (!eqs) {
    const auto& sys = f_.natural(chart);
    eqs = std::make_shared<const model::CompiledSystem>(pick(sys.equations, rows_except(sys.equations.size(), dropped)),
                                                        sys.unknowns.size());
  }
  return eqs;
}

const std::optional<CoordinateSubspace>& ArcSystems::subspace(std::uint64_t chart) {
  auto it = subspace_.find(chart);
  if (it == subspace_.end()) {
    const auto& sys = f_.natural(chart);
    it = subspace_.emplace(chart, coordinate_subspace(sys.equations, sys.unknowns.size())).first;
  }
  return it->second;
}

const std::shared_ptr<const model::CompiledSystem>& ArcSystems::for_exclusion(std::uint64_t chart,
                                                                             int subspace_variable) {
  if (subspace_variable < 0) return kept(chart, {});
  const auto& s = subspace(chart);
  return kept(chart, s ? dropped_for(*s, 0) : std::vector<int>{});
}

bool ArcSystems::reprove(MapArc& a, int subspace_variable) {
  const auto& sys = f_.natural(a.chart);
  for (int d : a.dropped)
    if (d < 0 || d >= static_cast<int>(sys.equations.size())) return false;
  a.arc = newton::arc_from(kept(a.chart, a.dropped), a.arc.box, a.arc.parameter, a.arc.preconditioner);
  if (!a.arc.certified) return false;
  if (subspace_variable < 0) return a.dropped.empty();
  const auto& s = subspace(a.chart);
  return s && s->variable == subspace_variable && spans_on_subspace(*s, a.arc.box, a.arc.parameter);
}

constexpr double kHalo = 4;

Near near_singular(const std::vector<SingularPoint>& points, std::uint64_t chart, const Box& piece) {
  Near out = Near::apart;
  for (auto& p : points) {
    const Box u = p.where();
    if (p.chart != chart || u.size() != piece.size()) continue;
    if (contains(u, piece)) return Near::inside;
    // Branches at a distance d from the point are about d apart: pieces within kHalo widths of
    // U are walked deeper too.
    Box halo = u;
    for (auto& x : halo) x = x + Interval(-kHalo, kHalo) * Interval(width(x));
    if (overlaps(halo, piece)) out = Near::meets;
  }
  return out;
}

bool piece_empty(const std::vector<model::Polynomial>& all, const std::shared_ptr<const model::CompiledSystem>& kept,
                 const Box& piece) {
  for (auto& e : all)
    if (excludes_zero(e.eval(piece))) return true;
  return newton::arc_excluded(kept, piece);
}

void join_arcs(const formulate::Formulation& f, const std::vector<Box>& members, CurveMap& map) {
  const size_t count = map.arcs.size();
  std::vector<size_t> parent(count);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<bool> touches_boundary(count, false);
  std::vector<std::pair<size_t, size_t>> ends_in;  // (arc, singular point)
  map.undecided_ends = map.loose_ends = 0;
  for (size_t a = 0; a < count; ++a) {
    const MapArc& ma = map.arcs[a];
    const Box& domain = f.natural(ma.chart).domain;
    for (int side = 0; side < 2; ++side) {
      // An end on the boundary needs no continuation, but is joined like any other: the
      // proof that every shared point is found needs every end.
      const bool boundary = on_domain_boundary(ma.arc, side, domain);
      touches_boundary[a] = touches_boundary[a] || boundary;
      std::map<std::uint64_t, std::optional<Box>> carried;
      // Inside a singular point's box the branches are not followed: an end there stops
      // there, whatever other arcs also hold it.
      const SingularPoint* p = singular_holding(f, map.singular_points, ma.arc.ends[side], ma.chart);
      if (p) ends_in.emplace_back(a, static_cast<size_t>(p - map.singular_points.data()));
      bool continued = boundary || p;
      for (size_t c = 0; c < count; ++c) {
        if (c == a) continue;
        const MapArc& mc = map.arcs[c];
        auto it = carried.find(mc.chart);
        if (it == carried.end()) it = carried.emplace(mc.chart, in_chart(f, ma.arc.ends[side], ma.chart, mc.chart)).first;
        const auto& end = it->second;
        if (!end) {
          ++map.undecided_ends;
          continue;
        }
        if (disjoint(*end, mc.arc.box)) continue;
        if (contains(mc.arc.box, *end)) {
          continued = true;
          parent[find(parent, a)] = find(parent, c);
        } else if (!disjoint(*end, mc.arc.image)) {
          ++map.undecided_ends;  // in the box's enclosure of its arc, astride the box
        }
      }
      if (!continued) ++map.loose_ends;
    }
  }
  std::map<size_t, size_t> component_of;
  map.components.clear();
  for (size_t a = 0; a < count; ++a) {
    const size_t root = find(parent, a);
    auto [it, fresh] = component_of.emplace(root, map.components.size());
    if (fresh) {
      map.components.emplace_back();
      map.components.back().closed = true;
    }
    MapComponent& c = map.components[it->second];
    c.arcs.push_back(a);
    c.closed = c.closed && !touches_boundary[a];
    const Box& m = members.at(map.arcs[a].member);
    c.extent = c.extent.empty() ? m : hull(c.extent, m);
  }
  // Per singular point, the components that reach its box.
  std::vector<std::set<size_t>> reaching(map.singular_points.size());
  for (auto [a, p] : ends_in) {
    MapComponent& c = map.components[component_of.at(find(parent, a))];
    c.closed = false;
    ++c.singular_ends;
    reaching[p].insert(component_of.at(find(parent, a)));
  }
  for (size_t p = 0; p < reaching.size(); ++p) map.singular_points[p].branches = static_cast<int>(reaching[p].size());
  map.proved = map.unresolved.empty() && map.undecided_ends == 0 && map.loose_ends == 0 &&
               count > 0;
  if (map.subspace_variable >= 0 && !map.charts.empty()) {
    const auto& names = f.natural(map.charts[0]).unknowns;
    const size_t k = static_cast<size_t>(map.subspace_variable);
    map.argument = k < names.size() ? names[k] : "x" + std::to_string(k);
  }
  state_map(map);
}

bool maps_apart(const formulate::Formulation& f, const CurveMap& a, const CurveMap& b) {
  auto ends_miss = [&](const CurveMap& from, const CurveMap& to) {
    for (auto& ma : from.arcs)
      for (auto& end : ma.arc.ends)
        for (auto& mc : to.arcs) {
          const auto e = in_chart(f, end, ma.chart, mc.chart);
          if (!e || !disjoint(*e, mc.arc.box)) return false;
        }
    return true;
  };
  return ends_miss(a, b) && ends_miss(b, a);
}

namespace {

using Sample = std::map<size_t, std::optional<MapArc>>;

// Walks every member's pieces into map.arcs and map.unresolved (the sample's arcs used for
// whole members); false when too many members stay unresolved to state a map.
template <class Prove>
bool walk_members(const formulate::Formulation& f, const std::vector<Box>& members, ArcSystems& systems,
                  CurveMap& map, Sample sample, Prove&& prove) {
  std::vector<size_t> unresolved_members;
  for (size_t k = 0; k < members.size(); ++k) {
    const std::uint64_t chart = map.charts[k];
    const auto& sys = f.natural(chart);
    const auto& exclusion = systems.for_exclusion(chart, map.subspace_variable);
    Box natural;
    try {
      natural = f.output_to_natural(chart, members[k]);
    } catch (const std::exception&) {
      return false;
    }
    bool unresolved = false, whole = true;
    walk_pieces(
        natural, [&](const Box& piece) { return near_singular(map.singular_points, chart, piece); },
        [&](const Box& piece) {
          // The walk asks for the whole member first, which the sample may have tried.
          auto tried = whole ? sample.find(k) : sample.end();
          whole = false;
          auto a = tried != sample.end() ? std::move(tried->second) : prove(k, piece);
          if (!a) return false;
          map.arcs.push_back(std::move(*a));
          return true;
        },
        [&](const Box& piece) { return piece_empty(sys.equations, exclusion, piece); },
        [&](const Box& piece, PieceKind kind) {
          if (kind != PieceKind::unresolved) return;
          map.unresolved.emplace_back(k, piece);
          unresolved = true;
        });
    if (unresolved) unresolved_members.push_back(k);
    if (too_many_unresolved(unresolved_members.size(), k + 1)) return false;
  }
  return true;
}

// Failed tries at a singular point before the rest of the unresolved pieces are left as they
// are, and U's reach around a piece, in piece widths.
constexpr int kSingularTries = 8;
constexpr double kSingularReach = 4;

// Proves singular points from the unresolved pieces of a map of n - 1 equations (one try per
// piece not already by a found one); true when it found any.
bool find_singular_points(const formulate::Formulation& f, CurveMap& map, const newton::NewtonOptions& options) {
  if (map.subspace_variable >= 0) return false;
  // A polynomial case has one natural system, whatever the chart.
  if (f.kind() == "polynomial" && !map.unresolved.empty() &&
      !known_coefficients(f.natural(map.charts[map.unresolved[0].first]).equations)) {
    map.inexact_coefficients = true;
    return false;
  }
  int failures = 0;
  for (auto& [member, piece] : map.unresolved) {
    const std::uint64_t chart = map.charts[member];
    if (failures >= kSingularTries) break;
    if (near_singular(map.singular_points, chart, piece) != Near::apart) continue;
    auto p = prove_singular_point(f.natural(chart).equations, chart, piece, kSingularReach * max_width(piece), options);
    const bool known = p && std::any_of(map.singular_points.begin(), map.singular_points.end(), [&](auto& q) {
      return q.chart == chart && q.point == p->point;
    });
    if (!p || known) {
      failures += !p;
      continue;
    }
    map.singular_points.push_back(std::move(*p));
  }
  return !map.singular_points.empty();
}

}  // namespace

std::optional<CurveMap> map_cluster(const formulate::Formulation& f, const std::vector<Box>& members,
                                    const std::vector<std::uint64_t>& charts, const newton::NewtonOptions& options) {
  const auto& first = f.natural(charts.at(0));
  const size_t n = first.unknowns.size(), m = first.equations.size();
  // Links (y = f(a)) are constraints the arcs' polynomial systems leave out.
  if (n < 2 || members.empty() || !first.links.empty()) return std::nullopt;
  ArcSystems systems(f);
  CurveMap map;
  map.charts = charts;
  map.equations = rows_except(m, {});
  if (m + 1 != n) {
    const auto& s = systems.subspace(charts[0]);
    if (!s) return std::nullopt;
    map.subspace_variable = s->variable;
  }
  auto prove = [&](size_t k, const Box& piece) {
    return prove_arc(f, systems, map.subspace_variable, k, charts[k], piece, options);
  };
  auto sample = sample_arcs(f, members, charts, prove);
  if (sample.empty() || !walk_members(f, members, systems, map, std::move(sample), prove)) return std::nullopt;
  // Pieces inside a singular point's box are covered by it, and the ones beside it are walked
  // deeper: the members are walked again, as the checker walks them.
  if (!map.unresolved.empty() && find_singular_points(f, map, options)) {
    map.arcs.clear();
    map.unresolved.clear();
    if (!walk_members(f, members, systems, map, {}, prove)) return std::nullopt;
  }
  if (map.arcs.empty()) return std::nullopt;
  map.singular_regions = regions(f, map, f.outputs_are_angles());
  join_arcs(f, members, map);
  return map;
}

}  // namespace linkbox::verify
