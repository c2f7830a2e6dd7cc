#pragma once
// Certified maps of curve clusters. Each member box of a cluster is covered by pieces (the
// box in its chart's natural unknowns, bisected where needed): on each, either an arc
// certificate (newton/arc.hpp) shows that the zero set of the kept equations there is exactly
// one arc, or evaluation shows that an equation misses 0. Arcs are then joined where an end
// of one lies in the box of another, into components.
//
// Why the components are exact: if two arcs a and c share a point, follow the common part
// within both boxes; it can leave a box only through that box's parameter faces (an arc
// never touches its other faces), so one end of a lies in the box of c or one end of c in the
// box of a, and that end is a point of the other's arc (the zero set in a box is its arc).
// So every shared point shows as an end inside another box, decided on the ends' enclosures;
// an enclosure that straddles a box is not decided, and the map is then not proved.
#include "formulate/formulation.hpp"
#include "newton/arc.hpp"
#include "verify/coordinate_subspace.hpp"
#include "verify/singular_point.hpp"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace linkbox::verify {

struct MapArc {
  size_t member = 0;        // index into the cluster's boxes
  std::uint64_t chart = 0;  // the natural unknowns the arc is in
  Box piece;                // the part of the member's natural box the arc covers
  newton::Arc arc;
  // A symmetric loop's arc (verify/symmetric_map.hpp): the rows of D and the preconditioner
  // of its uniqueness test in v (rows[0] < 0: an arc of the kept equations).
  Eigen::MatrixXd v_preconditioner;
  // A map through a coordinate subspace (verify/coordinate_subspace.hpp): the equations the
  // arc's certificate leaves out.
  std::vector<int> dropped;
};

struct MapComponent {
  std::vector<size_t> arcs;  // indices into CurveMap::arcs
  bool closed = false;       // every arc end continued by another arc
  int singular_ends = 0;     // arc ends inside a singular point's box
  Box extent;                // output variables: hull of the members its arcs cover
};

struct CurveMap {
  // What the arcs are arcs of: "" for n - 1 of the natural equations; "symmetric loop" for a
  // six-joint loop's reduced system (verify/symmetric_map.hpp), whose arcs are in u; with a
  // subspace_variable, that variable's name (for the statement).
  std::string argument;
  std::vector<std::uint64_t> charts;  // per member: the chart its pieces are in
  std::vector<int> equations;  // natural equations whose zero set the arcs are (all, n - 1)
  // >= 0: the system is redundant, and each arc is also one of the rest on x_k = 0 with this
  // k (verify/coordinate_subspace.hpp); `equations` are then all of them.
  int subspace_variable = -1;
  std::vector<MapArc> arcs;
  std::vector<std::pair<size_t, Box>> unresolved;  // (member, piece): no arc, not proved empty
  std::vector<MapComponent> components;
  // Groups of touching unresolved pieces (output variables): where a singular point may be.
  std::vector<Box> singular_regions;
  // Proved singular points (verify/singular_point.hpp): pieces inside one's box U are
  // covered by it, and arcs may end there. What the solution set is inside U, beyond its
  // one singular point, is not stated.
  std::vector<SingularPoint> singular_points;
  // A polynomial case whose equations have a coefficient with no known exact value (pi,
  // sqrt(2)): no singular point can be proved (exact arithmetic needs the coefficients).
  bool inexact_coefficients = false;
  int undecided_ends = 0;  // end enclosures that straddle another arc's box
  int loose_ends = 0;      // ends inside the domain that no other arc's box holds
  // The solution set in the cluster's boxes, outside the singular points' boxes, is exactly
  // the union of the components, each a smooth closed curve or an arc ending on the
  // domain's boundary or in a singular point's box.
  bool proved = false;
  std::string statement;  // the map in words, with what is not proved and why
};

// The systems a map's arcs are arcs of, per chart, compiled once: the kept equations (all but
// an arc's dropped ones) and, for a redundant system, the chart's coordinate subspace.
class ArcSystems {
 public:
  explicit ArcSystems(const formulate::Formulation& f) : f_(f) {}
  const std::shared_ptr<const model::CompiledSystem>& kept(std::uint64_t chart, const std::vector<int>& dropped);
  const std::optional<CoordinateSubspace>& subspace(std::uint64_t chart);
  // What an exclusion by arc_excluded is tried on: n - 1 of the equations.
  const std::shared_ptr<const model::CompiledSystem>& for_exclusion(std::uint64_t chart, int subspace_variable);
  // The arc re-proved from its box, parameter and preconditioner (image and ends recomputed)
  // and, with a subspace, its span there; false when a test fails.
  bool reprove(MapArc& a, int subspace_variable);

 private:
  const formulate::Formulation& f_;
  std::map<std::pair<std::uint64_t, std::vector<int>>, std::shared_ptr<const model::CompiledSystem>> kept_;
  std::map<std::uint64_t, std::optional<CoordinateSubspace>> subspace_;
};

// Bisection depth of a member's pieces: at most 2^kMapDepth pieces per member, and
// kSingularDepth more near a singular point's box (the branches beside it are as close as
// the distance to it).
constexpr int kMapDepth = 5;
constexpr int kSingularDepth = 12;

// What covers one piece: an arc, an exclusion, a singular point's box, or neither at the
// depth limit.
enum class PieceKind { arc, empty, singular, unresolved };

// Where a piece lies with respect to the singular points' boxes of its chart: inside one, or
// within a few of its widths.
enum class Near { apart, meets, inside };
Near near_singular(const std::vector<SingularPoint>& points, std::uint64_t chart, const Box& piece);

// Walks the pieces of a member's natural box `box` as the map covers it: inside a singular
// point's box (`near`), then `is_arc(piece)`, then `is_empty(piece)`, then bisection (widest
// side, at the midpoint) down to the depth; `leaf` hears every final piece. Producer and
// checker walk the same tree.
template <class Nearness, class IsArc, class IsEmpty, class Leaf>
void walk_pieces(const Box& box, Nearness&& near, IsArc&& is_arc, IsEmpty&& is_empty, Leaf&& leaf, int depth = 0) {
  const Near where = near(box);
  if (where == Near::inside) return leaf(box, PieceKind::singular);
  if (is_arc(box)) return leaf(box, PieceKind::arc);
  if (is_empty(box)) return leaf(box, PieceKind::empty);
  if (depth >= kMapDepth + (where == Near::meets ? kSingularDepth : 0)) return leaf(box, PieceKind::unresolved);
  auto [lo, hi] = bisect(box, widest_dimension(box));
  walk_pieces(lo, near, is_arc, is_empty, leaf, depth + 1);
  walk_pieces(hi, near, is_arc, is_empty, leaf, depth + 1);
}

// Whether a piece provably holds no solution: an equation of `all` misses 0 over it, or the
// kept equations have no root there (newton::arc_excluded). Both recomputed by the checker.
bool piece_empty(const std::vector<model::Polynomial>& all, const std::shared_ptr<const model::CompiledSystem>& kept,
                 const Box& piece);

// The map of a cluster whose members (output variables, unwrapped) lie in `charts`; empty
// when the natural system has links (y = f(a)), or is neither n - 1 equations in n unknowns
// nor redundant through a coordinate subspace (a mobile loop's closure needs an argument this map does not make), or
// when arcs hold on too few of the members to state one.
std::optional<CurveMap> map_cluster(const formulate::Formulation& f, const std::vector<Box>& members,
                                    const std::vector<std::uint64_t>& charts, const newton::NewtonOptions& options);

// Joins `map.arcs` into components and sets undecided_ends, loose_ends, proved and the
// statement. `members` are the cluster's boxes in output variables.
void join_arcs(const formulate::Formulation& f, const std::vector<Box>& members, CurveMap& map);

// Sets map.statement from its components, proved, unresolved pieces and ends.
void state_map(CurveMap& map);

// Whether no arc of `a` can share a point with an arc of `b` (maps of two clusters): by the
// argument above, a shared point shows as an end of one meeting the box of the other. Two
// clusters' boxes never touch, but an arc's box reaches beyond its piece, so this is what
// keeps one curve from being counted in two clusters.
bool maps_apart(const formulate::Formulation& f, const CurveMap& a, const CurveMap& b);

}  // namespace linkbox::verify
