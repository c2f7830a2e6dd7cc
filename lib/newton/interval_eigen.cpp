#include "newton/interval_eigen.hpp"

#include <vector>

namespace linkbox::newton {

IVector to_ivector(const Box& box) {
  IVector v(static_cast<Eigen::Index>(box.size()));
  for (size_t i = 0; i < box.size(); ++i) v(static_cast<Eigen::Index>(i)) = box[i];
  return v;
}

Box to_box(const IVector& v) { return Box(v.data(), v.data() + v.size()); }

IMatrix to_interval(const Eigen::MatrixXd& a) {
  IMatrix r(a.rows(), a.cols());
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j) r(i, j) = Interval(a(i, j));
  return r;
}

Eigen::MatrixXd midpoint(const IMatrix& a) {
  Eigen::MatrixXd r(a.rows(), a.cols());
  const NearestScope nearest;
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j) r(i, j) = nearest.median(a(i, j));
  return r;
}

Eigen::VectorXd midpoint(const IVector& v) {
  Eigen::VectorXd r(v.size());
  const NearestScope nearest;
  for (Eigen::Index i = 0; i < v.size(); ++i) r(i) = nearest.median(v(i));
  return r;
}

// The products below run inside one RoundingGuard on FastInterval: protected operations
// would switch the rounding mode twice per multiply-add, which was a third of the time of
// verifying a curve's boxes.

IVector multiply(const Eigen::MatrixXd& a, const IVector& x) {
  IVector r(a.rows());
  RoundingGuard guard;
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    FastInterval s(0.0);
    for (Eigen::Index k = 0; k < a.cols(); ++k) s += a(i, k) * as_fast(x(k));
    r(i) = as_protected(s);
  }
  return r;
}

IVector multiply(const IMatrix& a, const IVector& x) {
  IVector r(a.rows());
  RoundingGuard guard;
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    FastInterval s(0.0);
    for (Eigen::Index k = 0; k < a.cols(); ++k) s += as_fast(a(i, k)) * as_fast(x(k));
    r(i) = as_protected(s);
  }
  return r;
}

// A*B column by column over B's non-zero entries only: Jacobians of lifted and banded systems
// are mostly exact zeros, and a finite a(i,k) times [0,0] adds exactly nothing, so skipping
// them gives the same enclosure in n*nnz(B) steps instead of n^3. With a non-finite entry in
// A the product is formed densely, so that inf*0 still gives its NaN.
namespace {
IMatrix product(const Eigen::MatrixXd& a, const IMatrix& b, bool minus) {
  IMatrix r(a.rows(), b.cols());
  const bool sparse = a.allFinite();
  std::vector<FastInterval> s(static_cast<size_t>(a.rows()));
  RoundingGuard guard;
  for (Eigen::Index j = 0; j < b.cols(); ++j) {
    // Start from the identity entry so the cancellation 1 - (AB)_ii happens inside one
    // outward-rounded accumulation.
    for (Eigen::Index i = 0; i < a.rows(); ++i) s[i] = FastInterval(minus && i == j ? 1.0 : 0.0);
    for (Eigen::Index k = 0; k < a.cols(); ++k) {
      const Interval& bkj = b(k, j);
      if (sparse && bkj.lower() == 0 && bkj.upper() == 0) continue;
      const FastInterval x = as_fast(bkj);
      if (minus)
        for (Eigen::Index i = 0; i < a.rows(); ++i) s[i] -= a(i, k) * x;
      else
        for (Eigen::Index i = 0; i < a.rows(); ++i) s[i] += a(i, k) * x;
    }
    for (Eigen::Index i = 0; i < a.rows(); ++i) r(i, j) = as_protected(s[i]);
  }
  return r;
}
}  // namespace

IMatrix multiply(const Eigen::MatrixXd& a, const IMatrix& b) { return product(a, b, false); }

IMatrix identity_minus(const Eigen::MatrixXd& a, const IMatrix& b) { return product(a, b, true); }

double norm_inf_upper(const IMatrix& a) {
  RoundingGuard up;  // add_up below rounds towards +inf
  double best = 0;
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    double row = 0;
    for (Eigen::Index j = 0; j < a.cols(); ++j) {
      double m = std::max(std::fabs(a(i, j).lower()), std::fabs(a(i, j).upper()));
      if (std::isnan(m)) return kInf;
      row = up.add_up(row, m);
    }
    best = std::max(best, row);
  }
  return best;
}

}  // namespace linkbox::newton
