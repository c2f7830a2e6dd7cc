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
#include "model/vector_algebra.hpp"

#include <array>
#include <cstdint>

namespace linkbox::formulate {

// A quaternion (w, x, y, z) with polynomial entries: a rotation written in half-angle
// tangents, not normalised (it rotates v to Q v Q* / |Q|^2).
using QuaternionPolynomial = model::Quaternion<model::Polynomial>;

// A factor of a rotation chain and its squared norm |q|^2, kept as the exact polynomial
// (1 + t^2 or 1) rather than expanded from q, so that dividing by it is exact.
struct RotationFactor {
  QuaternionPolynomial q;
  model::Polynomial norm2;
};

// Rz(angle) with angle = 2 atan(t) (+ pi when bit `variable` of `chart` is set), t the
// unknown `variable`: q = 1 + t k (or k (1 + t k)), |q|^2 = 1 + t^2.
RotationFactor rotation_about_z(int variable, std::uint64_t chart);
// Rz(theta) for a constant angle, and Rx(alpha): unit quaternions with interval entries.
RotationFactor fixed_rotation_about_z(const Interval& theta);
RotationFactor rotation_about_x(const Interval& alpha);

// `variable[i]`: the unknown of entry i of the loop: the half-angle tangent of a revolute
// joint (shifted when bit `variable[i]` of `chart` is set) or the offset of a prismatic one.
// Returns the 3 rotation equations, then the 3 translation equations.
std::vector<model::Polynomial> dh_loop_closure(const input::LinkageLoop& loop, const std::vector<int>& variable,
                                               std::uint64_t chart);

}  // namespace linkbox::formulate
