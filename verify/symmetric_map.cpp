#include "verify/symmetric_map.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace linkbox::verify {

using newton::IMatrix;
using newton::IVector;

namespace {

Box u_of(const Box& uv) { return Box(uv.begin(), uv.begin() + 3); }

Box with_v(const Box& u, const Box& uv) {
  Box r = u;
  r.insert(r.end(), uv.begin() + 3, uv.end());
  return r;
}

std::array<int, 2> others(int p) { return p == 0 ? std::array{1, 2} : p == 1 ? std::array{0, 2} : std::array{0, 1}; }

bool finite(const Box& b) {
  for (auto& x : b)
    if (!is_finite(x)) return false;
  return true;
}

// The parametric Krawczyk image of Y (the sides other than p) over u, in mean-value form in
// the parameter too: K = y^ - C R(t^, y^) - C R_t(U) ([t] - t^) + (I - C R_y(U)) (Y - y^).
// Returns the image; `interior` when strictly inside Y.
Box reduced_image(const SymmetricLoop& loop, const Box& u, int p, const Eigen::MatrixXd& c, bool& interior) {
  const auto y = others(p);
  const IMatrix j = loop.r_jacobian(u);
  const Box mid = centre_box(u);
  const IVector r = loop.r_values(mid);
  IVector rhs(2), offset(2);
  IMatrix jy(2, 2);
  // The few sums here under one RoundingGuard: protected operations each switch the mode.
  {
    RoundingGuard guard;
    for (int i = 0; i < 2; ++i) {
      rhs(i) = as_protected(as_fast(r(i)) + as_fast(j(i, p)) * (as_fast(u[p]) - as_fast(mid[p])));
      offset(i) = as_protected(as_fast(u[y[i]]) - as_fast(mid[y[i]]));
      for (int k = 0; k < 2; ++k) jy(i, k) = j(i, y[k]);
    }
  }
  const IVector cr = newton::multiply(c, rhs), step = newton::multiply(newton::identity_minus(c, jy), offset);
  Box image(2);
  RoundingGuard guard;
  interior = true;
  for (int i = 0; i < 2; ++i) {
    image[i] = as_protected(as_fast(mid[y[i]]) + (as_fast(step(i)) - as_fast(cr(i))));
    interior = interior && is_finite(image[i]) && u[y[i]].lower() < image[i].lower() &&
               image[i].upper() < u[y[i]].upper();
  }
  return image;
}

// The arc's point on the face t = value, tightened by Krawczyk steps within the arc's box
// until its sides are a ten-thousandth of the box's: ends are only ever tested for lying
// inside another arc's box, which is grown from a whole piece.
Box end_at(const SymmetricLoop& loop, const Box& u, int p, double value, const Eigen::MatrixXd& c) {
  Box e = u;
  e[p] = Interval(value);
  const auto y = others(p);
  const auto tight = [&] {
    for (int i = 0; i < 2; ++i)
      if (width_up(e[y[i]]) > 1e-4 * width_up(u[y[i]])) return false;
    return true;
  };
  for (int step = 0; step < 6 && !tight(); ++step) {
    bool interior = false;
    const Box image = reduced_image(loop, e, p, c, interior);
    for (int i = 0; i < 2; ++i)
      if (!intersect(e[y[i]], image[i], e[y[i]])) return e;
  }
  return e;
}

// Float Newton on R with side p held at its midpoint, from x.
std::optional<Eigen::Vector3d> newton_point(const SymmetricLoop& loop, Eigen::Vector3d x, int p) {
  const auto y = others(p);
  Eigen::Vector2d r;
  Eigen::Matrix<double, 2, 3> j;
  for (int it = 0; it < 12; ++it) {
    loop.r_at(x, r, j);
    Eigen::Matrix2d jy;
    jy << j(0, y[0]), j(0, y[1]), j(1, y[0]), j(1, y[1]);
    const Eigen::Vector2d d = jy.partialPivLu().solve(r);
    if (!d.allFinite()) return std::nullopt;
    x(y[0]) -= d(0);
    x(y[1]) -= d(1);
    if (d.lpNorm<Eigen::Infinity>() < 1e-15) break;
  }
  return x;
}

// R's Jacobian at a point, in floating point.
Eigen::Matrix<double, 2, 3> jacobian_at(const SymmetricLoop& loop, const Eigen::Vector3d& x) {
  Eigen::Vector2d r;
  Eigen::Matrix<double, 2, 3> j;
  loop.r_at(x, r, j);
  return j;
}

// Whether T(u) = I is excluded on u: the quaternion's scalar part stays inside (-1, 1).
bool not_identity(const SymmetricLoop& loop, const Box& u) {
  const Interval q = loop.q0(u);
  return -1 < q.lower() && q.upper() < 1;
}

// Whether the slice [lo, hi] of arc `a`'s parameter holds no solution of `from` (the arc's
// box, or a wider slice's image) inside the piece's U and the member (in output variables):
// Krawczyk steps shrink the slice to its image at v = 0 (every solution in the slice stays in
// each image), which must miss U's other two sides or, carried to the outputs, the member. A
// slice that meets them is halved, down to `depth` more levels: an arc passing just beside
// the member (a box beside the curve's extreme, whose (u, v) hull reaches the curve) is told
// apart on thinner slices.
bool slice_misses(const SymmetricLoop& loop, const newton::Arc& a, const Box& u, const Box& member, const Box& from,
                  double lo, double hi, int depth) {
  const int p = a.parameter;
  const auto y = others(p);
  Box slice = from;
  slice[p] = Interval(lo, hi);
  for (int step = 0; step < 4; ++step) {
    bool interior = false;
    const Box image = reduced_image(loop, slice, p, a.preconditioner, interior);
    for (int k = 0; k < 2; ++k) {
      if (!is_finite(image[k])) return false;
      if (!intersect(slice[y[k]], image[k], slice[y[k]])) return true;
    }
  }
  const auto meets = [](const Interval& x, const Interval& z) { return x.lower() <= z.upper() && z.lower() <= x.upper(); };
  if (!meets(slice[y[0]], u[y[0]]) || !meets(slice[y[1]], u[y[1]])) return true;
  Box on_arc(6, Interval(0.0));  // the slice's solutions: (t, y) at v = 0
  for (int k = 0; k < 3; ++k) on_arc[k] = slice[k];
  if (!overlaps(loop.to_output(on_arc), member)) return true;
  if (depth == 0) return false;
  const double mid = lo + (hi - lo) / 2;
  return slice_misses(loop, a, u, member, slice, lo, mid, depth - 1) &&
         slice_misses(loop, a, u, member, slice, mid, hi, depth - 1);
}

// Whether the arc `a` (certified) misses the U of a piece inside its box, or the member the
// piece was cut from, over each of 8 slices of the piece's parameter range (slice_misses).
bool arc_misses(const SymmetricLoop& loop, const newton::Arc& a, const Box& u, const Box& member) {
  Interval range;
  if (!intersect(u[a.parameter], a.box[a.parameter], range)) return true;
  constexpr int kSlices = 8, kDeeper = 4;
  const double step = width_up(range) / kSlices;
  // Each slice ends where the next begins (the same double), so together they cover the range;
  // on a range a few ulps wide the edges stop at its end.
  const auto edge = [&](int i) { return i == kSlices ? range.upper() : std::min(range.lower() + i * step, range.upper()); };
  for (int i = 0; i < kSlices; ++i)
    if (!slice_misses(loop, a, u, member, a.box, edge(i), edge(i + 1), kDeeper)) return false;
  return true;
}

}  // namespace

newton::Arc symmetric_arc_from(const SymmetricLoop& loop, const Box& u, int parameter, const Eigen::MatrixXd& c,
                               const Box& uv_piece, const SymmetricLoop::RowChoice& rows) {
  newton::Arc a;
  a.parameter = parameter;
  a.box = u;
  a.preconditioner = c;
  if (u.size() != 3 || uv_piece.size() != 6 || parameter < 0 || parameter > 2 || c.rows() != 2 || c.cols() != 2 ||
      !c.allFinite() || !finite(u) || !finite(uv_piece))
    return a;
  bool interior = false;
  const Box image = reduced_image(loop, u, parameter, c, interior);
  if (!interior || !not_identity(loop, u) || !loop.on_subspace(with_v(u, uv_piece), rows)) return a;
  a.certified = true;
  a.image = u;
  const auto y = others(parameter);
  for (int i = 0; i < 2; ++i) a.image[y[i]] = image[i];
  a.ends[0] = end_at(loop, u, parameter, u[parameter].lower(), c);
  a.ends[1] = end_at(loop, u, parameter, u[parameter].upper(), c);
  return a;
}

namespace {

// Whether a piece whose solutions all lie at v = 0 holds none: V misses 0, or R misses 0 on U
// while T(u) = I is excluded there.
bool reduced_empty(const SymmetricLoop& loop, const Box& uv) {
  for (int i = 3; i < 6; ++i)
    if (!zero_in(uv[i])) return true;
  const Box u = u_of(uv);
  if (!not_identity(loop, u)) return false;
  const IVector r = loop.r_values(u);
  if (excludes_zero(r(0)) || excludes_zero(r(1))) return true;
  // The mean-value form, tighter where U is narrow: R(U) within R(u^) + R_u(U) (U - u^).
  const Box mid = centre_box(u);
  const IVector r0 = loop.r_values(mid);
  const IMatrix j = loop.r_jacobian(u);
  {
    RoundingGuard guard;
    for (int i = 0; i < 2; ++i) {
      FastInterval range = as_fast(r0(i));
      for (int k = 0; k < 3; ++k) range += as_fast(j(i, k)) * (as_fast(u[k]) - as_fast(mid[k]));
      if (excludes_zero(range)) return true;
    }
  }
  return false;
}

// Whether the piece provably holds no solution; `on_subspace`: every solution in it has v = 0
// (known from a piece that holds it, or proved here on the way).
bool piece_empty(const SymmetricLoop& loop, const Box& uv, bool& on_subspace) {
  if (!on_subspace) {
    const IVector d = loop.d_values(uv);
    for (int i = 0; i < d.size(); ++i)
      if (excludes_zero(d(i))) return true;
    const auto rows = loop.choose_rows(uv);
    if (!rows) return false;
    if (loop.excluded(uv, *rows)) return true;
    on_subspace = loop.on_subspace(uv, *rows);
    if (!on_subspace) return false;
  }
  return reduced_empty(loop, uv);
}


// An arc certified through a piece, and the float point of it that its test started from.
struct FoundArc {
  MapArc arc;
  Eigen::Vector3d point;
};

// Tries an arc through the piece: parameters in order of the curve's speed across the piece,
// Y grown from the piece until the Krawczyk image falls inside it.
std::optional<FoundArc> certify_symmetric(const SymmetricLoop& loop, const Box& uv, size_t member) {
  for (int i = 3; i < 6; ++i)
    if (!zero_in(uv[i])) return std::nullopt;
  const Box u = u_of(uv);
  Eigen::Vector3d x(median(u[0]), median(u[1]), median(u[2]));
  const auto rows = loop.choose_rows(uv);
  if (!rows) return std::nullopt;
  const Eigen::Matrix<double, 2, 3> j0 = jacobian_at(loop, x);
  const Eigen::Vector3d tangent = Eigen::Vector3d(j0.row(0)).cross(Eigen::Vector3d(j0.row(1)));
  std::array<int, 3> order{0, 1, 2};
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return std::fabs(tangent(a)) / width_up(u[a]) > std::fabs(tangent(b)) / width_up(u[b]);
  });
  for (int p : order) {
    const auto at = newton_point(loop, x, p);
    if (!at) continue;
    const auto y = others(p);
    const Eigen::Matrix<double, 2, 3> j = jacobian_at(loop, *at);
    Eigen::Matrix2d jy;
    jy << j(0, y[0]), j(0, y[1]), j(1, y[0]), j(1, y[1]);
    const Eigen::FullPivLU<Eigen::Matrix2d> lu(jy);
    if (!lu.isInvertible()) continue;
    const Eigen::MatrixXd c = lu.inverse();
    Box box = u;
    const double overlap = std::ldexp(width_up(u[p]), -10);
    box[p] = u[p] + Interval(-overlap, overlap);
    for (int i = 0; i < 2; ++i) box[y[i]] = hull(box[y[i]], Interval((*at)(y[i])));
    for (int round = 0; round < 6; ++round) {
      for (int i = 0; i < 2; ++i) {
        const double r = 0.1 * width_up(box[y[i]]) + 1e-12;
        box[y[i]] = box[y[i]] + Interval(-r, r);
      }
      if (max_width(box) > 4 * max_width(u)) break;
      bool interior = false;
      const Box image = reduced_image(loop, box, p, c, interior);
      if (!interior) {
        for (int i = 0; i < 2; ++i) box[y[i]] = hull(image[i], u[y[i]]);
        if (!finite(box)) break;
        continue;
      }
      newton::Arc a = symmetric_arc_from(loop, box, p, c, uv, *rows);
      if (!a.certified) break;
      MapArc m;
      m.member = member;
      m.piece = uv;
      m.arc = std::move(a);
      m.v_preconditioner = rows->c;
      return FoundArc{std::move(m), *at};
    }
  }
  return std::nullopt;
}

size_t find(std::vector<size_t>& parent, size_t a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

// Joins arcs whose end lies in another's box; angles are unbounded, so every end must be.
void join(const std::vector<Box>& members, const std::vector<std::vector<size_t>>& covered, CurveMap& map) {
  const size_t count = map.arcs.size();
  std::vector<size_t> parent(count);
  std::iota(parent.begin(), parent.end(), 0);
  for (size_t a = 0; a < count; ++a)
    for (int side = 0; side < 2; ++side) {
      const Box& end = map.arcs[a].arc.ends[side];
      bool continued = false;
      for (size_t c = 0; c < count; ++c) {
        if (c == a || !overlaps(end, map.arcs[c].arc.box)) continue;
        if (contains(map.arcs[c].arc.box, end)) {
          continued = true;
          parent[find(parent, a)] = find(parent, c);
        } else if (overlaps(end, map.arcs[c].arc.image)) {
          ++map.undecided_ends;
        }
      }
      if (!continued) ++map.loose_ends;
    }
  std::map<size_t, size_t> component_of;
  for (size_t a = 0; a < count; ++a) {
    auto [it, fresh] = component_of.emplace(find(parent, a), map.components.size());
    if (fresh) map.components.push_back({{}, true, 0, {}});
    MapComponent& c = map.components[it->second];
    c.arcs.push_back(a);
    for (size_t k : covered[a]) c.extent = c.extent.empty() ? members.at(k) : hull(c.extent, members.at(k));
  }
  map.proved = map.unresolved.empty() && map.undecided_ends == 0 && map.loose_ends == 0 && count > 0;
  state_map(map);
}

// The recorded arc whose box holds the piece's U with a margin (so that an end of another
// arc inside the piece is inside that box); with every solution in the piece at v = 0, the
// piece's solutions are that arc's points over U.
std::optional<size_t> covering_arc(const CurveMap& map, const Box& uv) {
  Box u = u_of(uv);
  for (auto& x : u) {
    const double margin = std::ldexp(width_up(x), -10);
    x = x + Interval(-margin, margin);
  }
  for (size_t a = map.arcs.size(); a-- > 0;)
    if (contains(map.arcs[a].arc.box, u)) return a;
  return std::nullopt;
}

// One member's pieces, added to the map as they are decided.
struct MemberWalk {
  const SymmetricLoop& loop;
  const std::vector<Box>& members;
  size_t k;
  CurveMap& map;
  std::vector<std::vector<size_t>>& covered;  // per arc: the members whose pieces it covers
  bool unresolved = false;

  void walk(const Box& uv, bool on_subspace, int depth) {
    // (u, v) pieces cover more than the member: what lies outside it needs no proof.
    if (!overlaps(loop.to_output(uv), members[k]) || covered_by_arc(uv, on_subspace)) return;
    // Emptiness before a new arc: a box beside the curve that the search could not empty holds
    // no arc, though an arc test may succeed in a box grown from it toward the curve.
    if (piece_empty(loop, uv, on_subspace) || (on_subspace && new_arc(uv))) return;
    if (depth >= kSymmetricDepth) {
      map.unresolved.emplace_back(k, uv);
      unresolved = true;
      return;
    }
    auto [lo, hi] = bisect(uv, on_subspace ? widest_dimension(u_of(uv)) : widest_dimension(uv));
    walk(lo, on_subspace, depth + 1);
    walk(hi, on_subspace, depth + 1);
  }

  // A recorded arc's box holds the piece's U and every solution in the piece has v = 0 (tried
  // first with that arc's rows, which near it usually pass): the piece's solutions are the
  // arc's points over U.
  bool covered_by_arc(const Box& uv, bool on_subspace) {
    const auto a = covering_arc(map, uv);
    if (!a) return false;
    if (!on_subspace && !loop.on_subspace(uv, {map.arcs[*a].v_preconditioner})) {
      const auto rows = loop.choose_rows(uv);
      if (!rows || !loop.on_subspace(uv, *rows)) return false;
    }
    covered[*a].push_back(k);
    return true;
  }

  bool new_arc(const Box& uv) {
    auto a = certify_symmetric(loop, uv, k);
    if (!a) return false;
    // The arc's box holds the piece's U, and every solution in it lies on the arc: a piece
    // whose U the arc misses holds none. A float point of the arc inside U and the member (the
    // one its test started from, or one in the middle of a slice of arc_misses) shows that the
    // test could not prove a miss: a certified arc may always be recorded (its points are
    // solutions), so the float points only save the test.
    if (inside(a->point, uv) || sample_inside(a->arc.arc, a->point, uv) ||
        !arc_misses(loop, a->arc.arc, u_of(uv), members[k])) {
      map.arcs.push_back(std::move(a->arc));
      covered.push_back({k});
    }
    return true;
  }

  // Whether a float point of the arc in the middle of one of arc_misses's slices is inside.
  bool sample_inside(const newton::Arc& a, const Eigen::Vector3d& point, const Box& uv) const {
    Interval range;
    if (!intersect(uv[a.parameter], a.box[a.parameter], range)) return false;
    constexpr int kSamples = 8;
    for (int i = 0; i < kSamples; ++i) {
      Eigen::Vector3d x = point;
      x(a.parameter) = range.lower() + (i + 0.5) * width_up(range) / kSamples;
      const auto at = newton_point(loop, x, a.parameter);
      if (at && inside(*at, uv)) return true;
    }
    return false;
  }

  // Whether a float point (u, 0) lies strictly inside the piece's U and, in the outputs,
  // inside the member.
  bool inside(const Eigen::Vector3d& point, const Box& uv) const {
    Box on_arc(6, Interval(0.0));
    for (int i = 0; i < 3; ++i) {
      if (!(uv[i].lower() < point(i) && point(i) < uv[i].upper())) return false;
      on_arc[i] = Interval(point(i));
    }
    const Box out = loop.to_output(on_arc);
    for (size_t i = 0; i < out.size(); ++i)
      if (!(members[k][i].lower() < out[i].lower() && out[i].upper() < members[k][i].upper())) return false;
    return true;
  }
};

}  // namespace

std::optional<CurveMap> map_symmetric(const SymmetricLoop& loop, const std::vector<Box>& members) {
  CurveMap map;
  map.argument = "symmetric loop";
  map.charts.assign(members.size(), 0);
  std::vector<std::vector<size_t>> covered;  // per arc: the members whose pieces it covers
  size_t unresolved_members = 0;
  for (size_t k = 0; k < members.size(); ++k) {
    MemberWalk w{loop, members, k, map, covered};
    w.walk(loop.to_uv(members[k]), false, 0);
    unresolved_members += w.unresolved;
    if (k + 1 >= 8 && 2 * unresolved_members > k + 1) return std::nullopt;
  }
  if (map.arcs.empty()) return map.unresolved.empty() ? std::optional(map) : std::nullopt;
  join(members, covered, map);
  return map;
}

}  // namespace linkbox::verify
