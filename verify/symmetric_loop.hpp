#pragma once
// A loop of six revolute joints whose Denavit-Hartenberg parameters repeat with period three
// (entries i and i + 3 alike: the line-symmetric Bricard linkages, the mobile 6R, cyclohexane).
// Its closure T(theta_1..3) T(theta_4..6) = I, T the transform of three consecutive entries,
// is structurally redundant along its curves, so no square subsystem certifies them. What
// does, in u = (theta_1..3 + theta_4..6) / 2 and v = (theta_1..3 - theta_4..6) / 2:
//
//  - Swapping the halves conjugates the closure (T2 T1 = T1^-1 (T1 T2) T1), so (u, v) is a
//    solution exactly when (u, -v) is.
//  - D(u, v) = T(u + v) - T(u - v)^-1 vanishes at every solution, so A(u, v) = D(u, v) -
//    D(u, -v) does too, and A(u, 0) = 0 for every u. If, over U x W with W the hull of V and
//    0, every matrix in the interval Jacobian of three of A's entries in v is regular
//    (||I - C J|| < 1 for a float C), then A(u, .) restricted to them is one to one on W for
//    each u (mean value theorem, W convex), so its only root there is v = 0: every solution
//    in U x V has v = 0 (`on_subspace`).
//  - On v = 0 the closure is T(u)^2 = I: T(u) = I (the quaternion's scalar part is +-1) or a
//    half-turn whose axis is orthogonal to its translation, R(u) = (q_0, vec q . p) = 0: two
//    equations in three unknowns, regular along the curves. Where q_0 stays inside (-1, 1)
//    the solutions in U x V are exactly {(u, 0): R(u) = 0}.
// Everything is evaluated as the product of the three transforms (rigorous sin and cos, the
// derivative of one factor at a time), which stays tight on boxes where the expanded closure
// polynomials do not.
#include "formulate/formulation.hpp"
#include "newton/interval_eigen.hpp"

#include <array>
#include <optional>

namespace linkbox::formulate {
class LinkageFormulation;
}

namespace linkbox::verify {

class SymmetricLoop {
 public:
  // The loop of `f` when the case is one such loop (revolute joints, no limits, no angle
  // constraints) and its outputs are its six angles; `output_of[i]` is entry i's output.
  static std::optional<SymmetricLoop> of(const formulate::Formulation& f);
  // Loop `loop` of a linkage of several, entry i's angle being output output_of[i] (its
  // natural unknown, formulate::LinkageFormulation::loop_unknowns); to_output then fills
  // only the loop's six outputs.
  static std::optional<SymmetricLoop> of_loop(const formulate::LinkageFormulation& f, size_t loop,
                                              const std::vector<int>& output_of);

  // (u, v) of a box of output variables (angles), and back: rigorous hulls.
  Box to_uv(const Box& output) const;
  Box to_output(const Box& uv) const;

  // D's and A's 12 entries (rows 0-2 of the 4x4 matrices), and A's derivatives in v and in
  // u (12 x 3).
  newton::IVector d_values(const Box& uv) const;
  newton::IVector a_values(const Box& uv) const;
  newton::IMatrix a_jacobian_v(const Box& uv) const { return a_jacobian(uv, 1.0); }
  newton::IMatrix a_jacobian_u(const Box& uv) const { return a_jacobian(uv, -1.0); }
  // R(u) = (q_0, vec q . p) over u (3 sides) and its 2 x 3 Jacobian.
  newton::IVector r_values(const Box& u) const;
  newton::IMatrix r_jacobian(const Box& u) const;
  // R and its Jacobian at a point in floating point, with the parameters' midpoints: no
  // enclosure, for float Newton steps only.
  void r_at(const Eigen::Vector3d& u, Eigen::Vector2d& r, Eigen::Matrix<double, 2, 3>& j) const;
  Interval q0(const Box& u) const;

  // The three rows of A and the preconditioner that make the uniqueness test succeed at the
  // box's centre best (float: they only choose).
  struct RowChoice {
    Eigen::MatrixXd c;  // 3 x 12
  };
  std::optional<RowChoice> choose_rows(const Box& uv) const;
  // The test above over U x W.
  bool on_subspace(const Box& uv, const RowChoice& choice) const;
  // Whether the chosen rows of A have no root in the box, whatever u in U: the Krawczyk image
  // of V about its midpoint v^, with A(U, v^) in mean-value form in u, misses V. Since
  // A_u(u, 0) = 0, that form stays tight near the subspace.
  bool excluded(const Box& uv, const RowChoice& choice) const;

 private:
  std::array<int, 6> output_of_{};
  size_t outputs_ = 6;
  // Products run in FastInterval inside a RoundingGuard held by each public evaluation; the
  // same code in double gives r_at.
  using F = FastInterval;
  template <class T>
  struct Parameters {
    std::array<T, 3> a, d, cos_alpha, sin_alpha, cos_half_alpha, sin_half_alpha;
  };
  Parameters<F> p_;
  Parameters<double> mid_;  // p_'s midpoints
  template <class T>
  using M34 = std::array<std::array<T, 4>, 3>;
  using Angles = std::array<Interval, 3>;
  template <class T>
  struct Trig {
    std::array<T, 3> c, s;  // cos and sin of each angle
  };
  static Trig<F> trig(const Angles& theta);
  template <class T>
  static M34<T> affine_times(const M34<T>& x, const M34<T>& y, bool y33);
  // T(theta) (rows 0-2), or with factor k replaced by its derivative; `inverse`: T(theta)^-1.
  template <class T>
  static M34<T> chain(const Parameters<T>& p, const Trig<T>& t, int derivative, bool inverse);
  // The quaternion of T's rotation from the half angles' cos and sin.
  template <class T>
  static std::array<T, 4> quaternion(const Parameters<T>& p, const Trig<T>& half, int derivative);
  // R and its Jacobian from the angles' and the half angles' cos and sin.
  template <class T>
  static void r_and_jacobian(const Parameters<T>& p, const Trig<T>& full, const Trig<T>& half, std::array<T, 2>& r,
                             std::array<std::array<T, 3>, 2>& j);
  newton::IMatrix a_jacobian(const Box& uv, double sign) const;
};

// U x W of a box of u (3 sides, first) and v (3 sides): each side of v joined with 0.
Box toward_subspace(const Box& uv);

}  // namespace linkbox::verify
