// Float inverses of badly scaled matrices: a regular matrix whose rows and columns differ in
// scale by 1e15 is inverted (its plain rcond is below the singular threshold), a singular one
// is refused however it is scaled, and a well scaled one gets the plain LU's inverse.
#include "newton/certify.hpp"
#include "newton/regular_inverse.hpp"

#include <catch2/catch.hpp>

#include <Eigen/LU>

using namespace linkbox::newton;

namespace {

const double kMinRcond = NewtonOptions{}.singular_rcond;

// diag(rows) A diag(cols) for a well conditioned A.
Eigen::MatrixXd badly_scaled(const Eigen::MatrixXd& a, const Eigen::VectorXd& rows, const Eigen::VectorXd& cols) {
  return rows.asDiagonal() * a * cols.asDiagonal();
}

}  // namespace

TEST_CASE("regular_inverse: badly scaled but regular matrices are inverted", "[newton]") {
  Eigen::MatrixXd a(3, 3);
  a << 2, -1, 0.5, 1, 3, -1, 0.25, 1, 4;
  Eigen::VectorXd rows(3), cols(3);
  rows << 1e-15, 1, 3e7;
  cols << 1e9, 1e-6, 1;
  const Eigen::MatrixXd j = badly_scaled(a, rows, cols);
  REQUIRE(Eigen::PartialPivLU<Eigen::MatrixXd>(j).rcond() < kMinRcond);  // the plain test refuses it
  const auto c = regular_inverse(j, kMinRcond);
  REQUIRE(c);
  // C J = K^-1 (A^-1 A) K for J = R A K: undo the column scales to compare with I.
  const Eigen::MatrixXd unscaled = cols.asDiagonal() * (*c * j) * cols.cwiseInverse().asDiagonal();
  CHECK((unscaled - Eigen::MatrixXd::Identity(3, 3)).cwiseAbs().maxCoeff() < 1e-12);
  Eigen::VectorXd b(3);
  b << 1e-15, 2, -3e7;
  const auto x = regular_solve(j, b, kMinRcond);
  REQUIRE(x);
  CHECK(((j * *x - b).array() / (rows.array() * 10)).abs().maxCoeff() < 1e-12);
}

TEST_CASE("regular_inverse: singular matrices are refused at any scaling", "[newton]") {
  Eigen::MatrixXd a(3, 3);
  a << 1, 2, 3, 2, 4, 6.000000000000001, 1, 0, 1;  // rows 1 and 2 parallel up to one rounding
  Eigen::VectorXd rows(3), cols(3);
  rows << 1e-10, 1, 1e5;
  cols << 1, 1e-8, 1e3;
  CHECK_FALSE(regular_inverse(a, kMinRcond));
  CHECK_FALSE(regular_inverse(badly_scaled(a, rows, cols), kMinRcond));
  CHECK_FALSE(regular_solve(badly_scaled(a, rows, cols), Eigen::VectorXd::Ones(3), kMinRcond));
}

TEST_CASE("regular_inverse: a well scaled matrix gets the plain inverse", "[newton]") {
  Eigen::MatrixXd a(2, 2);
  a << 3, 1, -1, 2;
  const auto c = regular_inverse(a, kMinRcond);
  REQUIRE(c);
  CHECK(*c == Eigen::PartialPivLU<Eigen::MatrixXd>(a).inverse());
}
