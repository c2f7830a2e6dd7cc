#pragma once
// Float inverses and solves of a square matrix, refused when it is numerically singular. A
// badly scaled system (coefficients of 1e-15 beside 1, unknowns of 1e-10 beside 1) has a
// Jacobian whose plain reciprocal condition is tiny although it is regular; so a matrix that
// fails the plain test is judged again as D_r J D_c, each row and then each column scaled by a
// power of two to a largest entry in [1, 2). Powers of two scale exactly, and J^-1 =
// D_c (D_r J D_c)^-1 D_r. These only give preconditioners and Newton starts: every test that
// uses them is an interval test, sound for any matrix.
#include <Eigen/Core>

#include <optional>

namespace linkbox::newton {

std::optional<Eigen::MatrixXd> regular_inverse(const Eigen::MatrixXd& j, double min_rcond);
std::optional<Eigen::VectorXd> regular_solve(const Eigen::MatrixXd& j, const Eigen::VectorXd& b, double min_rcond);

}  // namespace linkbox::newton
