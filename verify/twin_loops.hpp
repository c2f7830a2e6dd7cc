#pragma once
// Two angle constraints that are one equation when two identical loops sit at one root.
//
// Take a linkage of two loops sharing one revolute joint J (entry e of both), the second
// placed from the first by its turn psi about J. Frames of links: F_i = F_{i-1} Rz(theta_i)
// Rx(alpha_i), so with the frame of the link before J as reference (z along J), the axis of
// the joint after J is Rz(theta_J) Rx(alpha_e) z and that of the joint before J is
// Rx(-alpha_{e-1}) z; the second loop's are the same rotated by Rz(psi). With
// Rx(a) z = (0, -sin a, cos a):
//   after:  d1 . d2 = sin a_e sin a'_e cos(psi + theta'_J - theta_J) + cos a_e cos a'_e
//   before: d1 . d2 = sin a_{e-1} sin a'_{e-1} cos psi + cos a_{e-1} cos a'_{e-1}
// (at closure roots, whichever way round the loop the formulation reaches an axis). So when
// theta'_J = theta_J, the twists at the two ends pair up ({a_e, a'_e} = {a_{e-1}, a'_{e-1}})
// and both constraints ask the same angle, the two constraints hold at the same psi: one
// implies the other. theta'_J = theta_J holds when both loops are rigid at one root: their
// closures are one real system up to renaming (the same links, J at the same entry, each
// pair of unknowns in the same chart), and the second loop's root lies where the first's is
// proved unique.
#include "formulate/linkage.hpp"

#include <optional>
#include <string>
#include <vector>

namespace linkbox::verify {

// A rigid loop's root: one root of its closure lies in `image`, and no other in `unique`
// (both over the loop's unknowns, in loop order).
struct RigidRoot {
  Box image, unique;
};

struct TwinConstraint {
  int implied_row = -1;  // the natural equation the other one implies at the loops' roots
  std::string how;
};

// The argument above for a linkage whose two loops have roots `roots` (nullopt: not rigid).
std::optional<TwinConstraint> twin_constraint(const formulate::LinkageFormulation& f, std::uint64_t chart,
                                              const std::vector<std::optional<RigidRoot>>& roots);

}  // namespace linkbox::verify
