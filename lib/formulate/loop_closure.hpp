#pragma once
// The loop closure of one Denavit-Hartenberg loop, prod_i Rz(theta_i) Tz(d_i) Tx(a_i)
// Rx(alpha_i) = I, as polynomials in the half-angle tangents of one chart: the natural
// square system in which linkage roots are certified (verify/), free of the vector model's
// dummy and redundant equations.
//   rotation:    vector part of prod_i q_i c_i, with q_i = (1 + t_i k) (times k when the
//                chart shifts joint i by a half turn) and c_i the quaternion of Rx(alpha_i);
//   translation: sum_i R_{<i} d_i z + R_{<=i} a_i x, with every rotation written
//                Q v Q* / |Q|^2 and the sum multiplied by prod_j (1 + t_j^2) > 0.
#include "formulate/linkage.hpp"

#include <cstdint>

namespace linkbox::formulate {

// `variable[i]`: the unknown of entry i of the loop: the half-angle tangent of a revolute
// joint (shifted when bit `variable[i]` of `chart` is set) or the offset of a prismatic one.
// Returns the 3 rotation equations, then the 3 translation equations.
std::vector<model::Polynomial> dh_loop_closure(const LinkageLoop& loop, const std::vector<int>& variable,
                                               std::uint64_t chart);

}  // namespace linkbox::formulate
