#pragma once
// Certified maps of a symmetric six-joint loop's curve clusters (verify/symmetric_loop.hpp).
// Each member is carried to (u, v) and covered by pieces: on each, either
//  - an arc: the uniqueness test in v holds over the arc's box U x V (so every solution there
//    has v = 0), q_0 stays inside (-1, 1) on U, and a parametric Krawczyk test on R over
//    U shows that R's zero set in U is exactly one arc, a graph over one side of U: then the
//    solution set in U x V is exactly that arc at v = 0; or
//  - covered: the uniqueness test holds over the piece and the box of an arc already found
//    holds its U (with a margin): the piece's solutions are that arc's points; or
//  - empty: an entry of D misses 0 over the piece, or the uniqueness test holds and V misses
//    0, or it holds and R misses 0 on U while T(u) = I is excluded there.
// Pieces are bisected at their widest side until the uniqueness test holds, then at their
// widest side in u only: what the test proves of a piece holds for its parts, and its
// solutions all lie at v = 0, so only U still needs to narrow.
// Arcs are joined as in curve_map.hpp (an end inside another arc's box), in u, where they are
// the zero sets of one function R.
#include "verify/curve_map.hpp"
#include "verify/symmetric_loop.hpp"

namespace linkbox::verify {

// The width (in the search's variables) a member should have before it is mapped, what
// `--narrow` should be given: wider pieces neither exclude nor certify, so the boxes are
// narrowed first (solve/narrow.hpp).
constexpr double kSymmetricPiece = 0.02;
// Members wider than this (output variables) are not mapped: their pieces would not resolve
// within the bisection depth.
constexpr double kSymmetricMember = 0.2;

// Bisection depth of a member's pieces.
constexpr int kSymmetricDepth = 18;

// The map of a cluster (members in output variables, unwrapped); empty when too few members
// hold arcs to state one. A map with no arcs and no unresolved pieces proves that the cluster
// holds no solution.
std::optional<CurveMap> map_symmetric(const SymmetricLoop& loop, const std::vector<Box>& members);

// The arc certificate re-proved from its box in u, parameter, preconditioner, the piece's v
// and the uniqueness test's rows and preconditioner; certified = false when a test fails.
newton::Arc symmetric_arc_from(const SymmetricLoop& loop, const Box& u, int parameter, const Eigen::MatrixXd& c,
                               const Box& uv_piece, const SymmetricLoop::RowChoice& rows);

}  // namespace linkbox::verify
