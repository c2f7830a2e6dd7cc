#pragma once
// Eigen matrices of linkbox::Interval, and the mixed double/interval products that Eigen
// cannot form by itself.
//
// Two pitfalls are guarded here:
//  * Boost's interval has an unconstrained `template <class T1> interval(const T1&)`, so
//    std::is_convertible<AnyEigenMatrix, Interval> is true. Eigen then offers
//    "matrix times scalar" alongside "matrix times matrix" and `A * x` is ambiguous. The
//    promote_scalar_arg specialisation below only lets arithmetic types act as scalars.
//  * Boost's comparisons throw when intervals overlap, so Eigen members that compare
//    scalars (maxCoeff, isApprox, norms, decompositions) must not be used on interval
//    matrices. Invert in double (see `midpoint`) and bound norms with `norm_inf_upper`.
#include "interval/box.hpp"

#include <Eigen/Core>

#include <limits>
#include <type_traits>

namespace Eigen {

template <>
struct NumTraits<linkbox::Interval> : GenericNumTraits<double> {
  using Real = linkbox::Interval;
  using NonInteger = linkbox::Interval;
  using Nested = linkbox::Interval;
  using Literal = linkbox::Interval;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 2,
    AddCost = 8,  // protected operations switch the rounding mode
    MulCost = 16
  };
  static inline Real epsilon() { return Real(std::numeric_limits<double>::epsilon()); }
  static inline Real dummy_precision() { return Real(1e-12); }
  static inline Real highest() { return Real(std::numeric_limits<double>::max()); }
  static inline Real lowest() { return Real(std::numeric_limits<double>::lowest()); }
  static inline int digits10() { return std::numeric_limits<double>::digits10; }
};

namespace internal {

struct linkbox_no_scalar_promotion {};  // no `type`: Eigen's scalar overload drops out

template <typename T>
struct promote_scalar_arg<linkbox::Interval, T, false>
    : std::conditional_t<std::is_arithmetic_v<T>,
                         promote_scalar_arg<linkbox::Interval, linkbox::Interval, true>,
                         linkbox_no_scalar_promotion> {};

}  // namespace internal
}  // namespace Eigen

namespace linkbox::newton {

using IMatrix = Eigen::Matrix<Interval, Eigen::Dynamic, Eigen::Dynamic>;
using IVector = Eigen::Matrix<Interval, Eigen::Dynamic, 1>;

IVector to_ivector(const Box& box);
Box to_box(const IVector& v);
IMatrix to_interval(const Eigen::MatrixXd& a);  // exact: each entry a point interval

// Entry-wise midpoints (for the float preconditioner; not rigorous by design).
Eigen::MatrixXd midpoint(const IMatrix& a);
Eigen::VectorXd midpoint(const IVector& v);

// Enclosures of A*x, A*B and I - A*B for a double matrix A: each entry of A is taken as an
// exact point, so the results contain the exact products.
IVector multiply(const Eigen::MatrixXd& a, const IVector& x);
IVector multiply(const IMatrix& a, const IVector& x);  // an interval A
IMatrix multiply(const Eigen::MatrixXd& a, const IMatrix& b);
IMatrix identity_minus(const Eigen::MatrixXd& a, const IMatrix& b);

// Upper bound of max_i sum_j max|a_ij| over every real matrix in `a` (rounded up).
double norm_inf_upper(const IMatrix& a);

}  // namespace linkbox::newton
