#pragma once
// Arc certificates: the zero set of n-1 equations in n variables over a box, proved to be
// exactly one smooth arc. With t the side `parameter` of B = [t] x Y, (t^, y) its midpoint
// and C a float matrix, the parametric Krawczyk image
//   K = y - C F(t^, y) - C F_t(B) ([t] - t^) + (I - C F_y(B)) (Y - y)
// contains K(t, Y) for every single t in [t]. Strictly inside Y, it proves for each t exactly
// one root y(t) in Y, and every F_y over B regular: the zero set in B is the graph of a smooth
// y(t) over the whole of [t], entering through the face t = lo and leaving through t = hi,
// and it never touches the other faces of B.
#include "model/compiled.hpp"
#include "newton/certify.hpp"

#include <array>
#include <memory>

namespace linkbox::newton {

struct Arc {
  bool certified = false;
  int parameter = -1;
  Box box;                          // B (all n variables)
  Eigen::MatrixXd preconditioner;   // C, (n-1) x (n-1), over the variables other than t
  Box image;                        // [t] x K([t], Y): holds the arc
  std::array<Box, 2> ends;          // hold the arc's points on t = lo and on t = hi
};

// Tries to prove an arc through `piece` (f: n-1 equations compiled over n variables). The
// parameter is the side the curve crosses the piece fastest along (relative to its width),
// then the others; Y grows from the piece's other sides until the test holds, inside
// `domain` (empty: unbounded). Float steps only choose; the result is re-proved by arc_from.
Arc certify_arc(const std::shared_ptr<const model::CompiledSystem>& f, const Box& piece, const Box& domain,
                const NewtonOptions& options = {});

// The certificate re-proved from (f, box, parameter, C) alone, image and ends recomputed
// (what certify_arc returns is exactly this); certified = false when the test fails.
Arc arc_from(const std::shared_ptr<const model::CompiledSystem>& f, const Box& box, int parameter,
             const Eigen::MatrixXd& preconditioner);

// arc_from with C the inverse of the midpoint Jacobian over `box` (computed from the box
// alone, so a checker recomputes the same test).
Arc arc_over(const std::shared_ptr<const model::CompiledSystem>& f, const Box& box, int parameter);

// Proves that the n-1 equations have no root in `box`: for some parameter p, the Krawczyk
// image of the other sides over box[p] (C: the inverse midpoint Jacobian there, computed from
// the box alone, so a checker recomputes the same test) misses them.
bool arc_excluded(const std::shared_ptr<const model::CompiledSystem>& f, const Box& box);

}  // namespace linkbox::newton
