#pragma once
// Singular points of a curve H = 0 (n - 1 polynomials in n unknowns): where H's Jacobian
// drops to rank n - 2, no arc certificate can hold, and branches may cross.
//
// Why a box U holds exactly one, at p. The augmented system
//   G(u, e, mu) = (H(u) - mu e, H'(u)^T e, l . e - 1)   (2n equations, 2n unknowns)
// is regular at a singular point whose second-order form is nondegenerate, so Krawczyk can
// prove a unique root of G in U x E x M. A contraction bound on the linear system
// (H'(u)^T; l^T) e = (0; 1) over U proves rank H'(u) >= n - 2 on U and every solution e in
// E; a singular point u of the curve in U then gives the root (u, e, 0) of G in the box, so
// U holds at most one. A rational p in U where exact arithmetic finds H(p) = 0 and rank n - 2
// is that one, and its second-order form says what it is (verify/exact_point.hpp).
#include "newton/certify.hpp"
#include "verify/exact_point.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace linkbox::verify {

struct SingularPoint {
  std::uint64_t chart = 0;         // the natural unknowns u are this chart's
  Box box;                         // U x E x M: u (n), e (n - 1), mu
  Eigen::MatrixXd preconditioner;  // Krawczyk's C for G over box
  std::vector<double> normal;      // l
  std::vector<std::string> point;  // p, exact rationals
  SingularKind kind = SingularKind::degenerate;
  int branches = 0;  // components of the map with an arc end inside U
  Box where() const;  // U
};

// A singular point near the middle of `piece` (natural unknowns of `chart`), with U as wide
// as the tests allow up to `reach` on each side of it; none when a step fails.
std::optional<SingularPoint> prove_singular_point(const std::vector<model::Polynomial>& h, std::uint64_t chart,
                                                  const Box& piece, double reach,
                                                  const newton::NewtonOptions& options);

// Re-proves a stated singular point from its box, C, l and p alone; sets its kind.
bool reprove_singular_point(const std::vector<model::Polynomial>& h, SingularPoint& s);

}  // namespace linkbox::verify
