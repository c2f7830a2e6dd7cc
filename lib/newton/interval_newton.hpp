#pragma once
// Interval Newton operators on a box X with a float preconditioner C, everything else in
// outward-rounded interval arithmetic. Their images contain every root of F in X, so
//   image inside the interior of X  => exactly one root in X (existence and uniqueness),
//   image disjoint from X           => no root in X.
// Both hold for any C; a good C (inverse of a midpoint Jacobian) only makes them succeed.
// The centre is y = midpoint of X, so anyone holding (F, X, C) recomputes the same image.
#include "newton/square_system.hpp"

#include <optional>

namespace linkbox::newton {

enum class Method {
  krawczyk,         // K(X) = y - C F(y) + (I - C F'(X)) (X - y)
  hansen_sengupta,  // Gauss-Seidel on C F'(X) (x - y) = -C F(y); tighter, needs 0 not in diagonal
};

struct NewtonStep {
  Box image;              // contains every root in X (Hansen-Sengupta: intersected with X)
  bool interior = false;  // image strictly inside X, all sides: unique root in X
  bool excluded = false;  // image misses X: no root in X
};

NewtonStep krawczyk_step(const SquareSystem& f, const Box& x, const Eigen::MatrixXd& c);
NewtonStep hansen_sengupta_step(const SquareSystem& f, const Box& x, const Eigen::MatrixXd& c);
NewtonStep newton_step(Method m, const SquareSystem& f, const Box& x, const Eigen::MatrixXd& c);

// Proves F has at most one root in box `y` (any size): the bound ||I - C F'(y)||_inf < 1
// makes every Jacobian in F'(y) regular, so F is injective on y (mean-value form).
bool at_most_one_root(const SquareSystem& f, const Box& y, const Eigen::MatrixXd& c);

// A Krawczyk preconditioner whose step excludes X where the midpoint Jacobian is (nearly)
// singular, as between the two roots of a close pair: every root makes u . F vanish,
// for any u, and with u a left singular vector of a small singular value, u . F'(X) is
// small over X, so the mean-value form u . F(y) + (u . F'(X)) (X - y) can miss 0 where no
// inverse is usable. As one row (alpha u, the others 0) of C that gives a Krawczyk image
// y_0 - alpha u . F(y) + (e_0 - alpha u . F'(X)) (X - y), whose side 0 misses X_0 once alpha
// times that form's distance from 0 exceeds X_0's width; alpha is taken large, so the form
// missing 0 by 2^-30 of |u . F(y)| suffices. The float SVD only chooses C; the step decides
// (none: no such C was found).
std::optional<Eigen::MatrixXd> combination_exclusion(const SquareSystem& f, const Box& x);

}  // namespace linkbox::newton
