#include "prune/newton_contractor.hpp"

#include <Eigen/LU>
#include <Eigen/QR>

#include <cmath>

namespace linkbox::prune {

IntervalNewton::IntervalNewton(const std::vector<model::Polynomial>& equations, size_t variables, Arith arith,
                               const std::vector<model::Link>& links)
    : system_(equations, links, variables, arith), arith_(arith) {}

// The float LU of the midpoint Jacobian: about n^3/50 operations on large systems, where
// Eigen's blocked kernels run; below n = 20 its n^2 bookkeeping dominates (measured, see
// papers/decisions/search.md). A step that finds the LU singular stops there.
double IntervalNewton::factor_operations() const {
  const double n = system_.cols();
  return n * n + std::floor(n * n * n / 50);
}

// Past the LU: the inverse in double (about n^3/5), then F(y), C F'(X), C F(y) and
// Gauss-Seidel in intervals.
double IntervalNewton::solve_operations() const {
  const double m = system_.rows(), n = system_.cols();
  return std::floor(n * n * n / 5) + n * (system_.nonzeros() + m + n) + system_.value_operations();
}

double IntervalNewton::step_operations() const {
  return system_.value_operations() + system_.jacobian_operations() + factor_operations() + solve_operations();
}

Outcome IntervalNewton::contract(Box& box) {
  return with_rounding(arith_, [&] { return step(box); });
}

Outcome IntervalNewton::step(Box& box) {
  unique_ = false;
  const int m = system_.rows(), n = system_.cols(), nnz = system_.nonzeros();
  f_.resize(m);
  j_.resize(nnz);
  system_.evaluate(box, f_.data(), j_.data());
  operations_ += system_.value_operations() + system_.jacobian_operations();
  // The range test: where the Jacobian is singular Newton removes nothing, this still does.
  for (int i = 0; i < m; ++i)
    if (excludes_zero(f_[i])) return Outcome::empty;
  if (m < n || n == 0) return Outcome::unchanged;
  operations_ += factor_operations();

  // The float preconditioner: only how much is removed depends on it.
  jm_.setZero(m, n);
  for (int e = 0; e < nnz; ++e) jm_(system_.entry_row(e), system_.entry_col(e)) = 0.5 * j_[e].lower() + 0.5 * j_[e].upper();
  if (!jm_.allFinite()) return Outcome::unchanged;
  if (m == n) {
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(jm_);
    // A singular midpoint Jacobian gives no preconditioner. The pivots' spread is a cheap
    // test of that; rcond() cost 8% of Eco9's run for the same answer.
    const auto pivots = lu.matrixLU().diagonal().cwiseAbs();
    if (!(pivots.minCoeff() > 1e-14 * pivots.maxCoeff())) return Outcome::unchanged;
    operations_ += solve_operations();
    c_ = lu.inverse();
  } else {
    operations_ += solve_operations();
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(jm_);
    if (cod.rank() < n) return Outcome::unchanged;
    c_ = cod.pseudoInverse();
  }
  if (!c_.allFinite()) return Outcome::unchanged;

  y_.resize(n);
  for (int i = 0; i < n; ++i) {
    if (!is_finite(box[i])) return Outcome::unchanged;
    y_[i] = std::clamp(0.5 * box[i].lower() + 0.5 * box[i].upper(), box[i].lower(), box[i].upper());
  }
  system_.values_at(y_.data(), f_.data());  // F(y), enclosed

  // A = C F'(X) (n x n) from the sparse Jacobian; b = -C F(y).
  a_.assign(static_cast<size_t>(n) * n, FastInterval(0.0));
  for (int e = 0; e < nnz; ++e) {
    const int r = system_.entry_row(e), k = system_.entry_col(e);
    for (int i = 0; i < n; ++i)
      if (const double c = c_(i, r); c != 0) a_[static_cast<size_t>(i) * n + k] += c * j_[e];
  }
  b_.assign(n, FastInterval(0.0));
  for (int i = 0; i < n; ++i)
    for (int r = 0; r < m; ++r)
      if (const double c = c_(i, r); c != 0) b_[i] -= c * f_[r];

  // Gauss-Seidel on A (x - y) = b, x - y in X - y, each row using the rows narrowed before it.
  d_.resize(n);
  for (int i = 0; i < n; ++i) d_[i] = FastInterval(box[i].lower(), box[i].upper()) - y_[i];
  bool interior = true;
  for (int i = 0; i < n; ++i) {
    const FastInterval& aii = a_[static_cast<size_t>(i) * n + i];
    if (!(aii.lower() > 0 || aii.upper() < 0)) {  // contains 0 (or NaN): this row proves nothing
      interior = false;
      continue;
    }
    FastInterval s = b_[i];
    for (int j = 0; j < n; ++j)
      if (j != i) s -= a_[static_cast<size_t>(i) * n + j] * d_[j];
    const FastInterval ni = s / aii;
    const FastInterval moved = y_[i] + ni;
    interior = interior && box[i].lower() < moved.lower() && moved.upper() < box[i].upper();
    // NaN bounds of ni drop out of max/min: nothing is narrowed on them.
    const double lo = std::max(d_[i].lower(), ni.lower()), hi = std::min(d_[i].upper(), ni.upper());
    if (!(lo <= hi)) return Outcome::empty;
    d_[i] = FastInterval(lo, hi);
  }
  unique_ = interior;

  bool shrunk = false;
  for (int i = 0; i < n; ++i) {
    const FastInterval x = y_[i] + d_[i];
    const double lo = std::max(box[i].lower(), x.lower()), hi = std::min(box[i].upper(), x.upper());
    if (!(lo <= hi)) return Outcome::empty;
    if (lo != box[i].lower() || hi != box[i].upper()) {
      box[i] = Interval(lo, hi);
      shrunk = true;
    }
  }
  return shrunk ? Outcome::shrunk : Outcome::unchanged;
}

}  // namespace linkbox::prune
