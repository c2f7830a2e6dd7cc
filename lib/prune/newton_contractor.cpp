#include "prune/newton_contractor.hpp"

#include "model/block_triangular.hpp"

#include <Eigen/LU>
#include <Eigen/QR>

#include <cmath>

namespace linkbox::prune {

namespace {

// A singular midpoint Jacobian gives no preconditioner. The pivots' spread is a cheap test of
// that; rcond() cost 8% of Eco9's run for the same answer.
bool regular(const Eigen::PartialPivLU<Eigen::MatrixXd>& lu) {
  const auto pivots = lu.matrixLU().diagonal().cwiseAbs();
  return pivots.minCoeff() > 1e-14 * pivots.maxCoeff();
}

// The float LU of the midpoint Jacobian: about n^3/50 operations on large systems, where
// Eigen's blocked kernels run; below n = 20 its n^2 bookkeeping dominates (measured, see
// papers/decisions/search.md). A step that finds the LU singular stops there.
double factor_price(double n) { return n * n + std::floor(n * n * n / 50); }

// Past the LU: the inverse in double (about n^3/5), then F(y), C F'(X), C F(y) and
// Gauss-Seidel in intervals.
double solve_price(double m, double n, double nonzeros, double value_operations) {
  return std::floor(n * n * n / 5) + n * (nonzeros + m + n) + value_operations;
}

}  // namespace

IntervalNewton::IntervalNewton(const std::vector<model::Polynomial>& equations, size_t variables, Arith arith,
                               const std::vector<model::Link>& links, const std::vector<int>& substitutable)
    : system_(equations, links, variables, arith), substitution_(system_, equations, substitutable), arith_(arith) {
  find_blocks();
}

// The blocks of a square system that separates (model/block_triangular.hpp): a fallback
// preconditioner where the whole midpoint Jacobian is singular.
void IntervalNewton::find_blocks() {
  const int m = equations(), n = unknowns();
  if (m != n) return;
  const model::BlockTriangular b = model::block_triangular(
      m, n, substitution_.empty() ? model::pattern_of(system_) : model::pattern_of(substitution_));
  if (!b.square || b.blocks < 2) return;
  for (int k : b.order) {
    if (blocks_.empty() || b.block[k] != b.block[blocks_.back().cols.front()]) blocks_.emplace_back();
    blocks_.back().cols.push_back(k);
    blocks_.back().rows.push_back(b.row[k]);
  }
}

double IntervalNewton::factor_operations() const { return factor_price(unknowns()); }

double IntervalNewton::solve_operations() const {
  return solve_price(equations(), unknowns(), nonzeros(), system_.value_operations());
}

double IntervalNewton::step_operations() const {
  return system_.value_operations() + system_.jacobian_operations() + substitution_.reduce_operations() +
         factor_operations() + solve_operations();
}

double IntervalNewton::step_operations_of(const std::vector<model::Polynomial>& equations, size_t variables,
                                          const std::vector<model::Link>& links) {
  const model::CompiledSystem::Shape s = model::CompiledSystem::shape_of(equations, links, variables);
  return s.value_operations + s.jacobian_operations + factor_price(s.cols) +
         solve_price(s.rows, s.cols, s.nonzeros, s.value_operations);
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
  const bool substituted = !substitution_.empty();
  if (substituted && !(midpoints(box) && substituted_jacobian(box))) return Outcome::unchanged;
  operations_ += factor_operations();
  if (!precondition()) return Outcome::unchanged;
  if (!substituted && !midpoints(box)) return Outcome::unchanged;
  if (substituted) system_.values(z_, f_.data());  // F(z) = G(y), enclosed
  else system_.values_at(y_.data(), f_.data());    // F(y), enclosed
  const Outcome out = gauss_seidel(box);
  if (out == Outcome::empty || !substituted) return out;
  bool narrowed = false;
  if (!substitution_.narrow(box, narrowed)) return Outcome::empty;
  return narrowed ? Outcome::shrunk : out;
}

bool IntervalNewton::midpoints(const Box& box) {
  const int n = unknowns();
  y_.resize(n);
  for (int i = 0; i < n; ++i) {
    const Interval& x = box[substitution_.empty() ? i : substitution_.col(i)];
    if (!is_finite(x)) return false;
    y_[i] = std::clamp(0.5 * x.lower() + 0.5 * x.upper(), x.lower(), x.upper());
  }
  return true;
}

// For a root x in X, G(x) - G(y) = G'(xi) (x - y) with xi on the segment from y: there each
// substituted v = L(xi) lies between L(y) and X_v (L is linear and L(x) is in X_v), so F' is
// evaluated with X_v widened to hold L(y) wherever it does not already.
bool IntervalNewton::substituted_jacobian(const Box& box) {
  z_ = box;
  for (int i = 0; i < unknowns(); ++i) z_[substitution_.col(i)] = Interval(y_[i]);
  substitution_.substitute(z_);
  widened_ = box;
  bool wider = false;
  for (size_t k = 0; k < box.size(); ++k) {
    if (!is_finite(box[k]) || !is_finite(z_[k])) return false;
    widened_[k] = hull(box[k], z_[k]);
    wider = wider || widened_[k].lower() != box[k].lower() || widened_[k].upper() != box[k].upper();
  }
  if (wider) {
    system_.jacobian(widened_, j_.data());
    operations_ += system_.jacobian_operations();
  }
  g_.resize(substitution_.nonzeros());
  substitution_.reduce(j_.data(), g_.data());
  operations_ += substitution_.reduce_operations();
  return true;
}

bool IntervalNewton::precondition() {
  const int m = equations(), n = unknowns();
  const FastInterval* j = jacobian();
  // The float preconditioner: only how much is removed depends on it.
  jm_.setZero(m, n);
  for (int e = 0; e < nonzeros(); ++e) jm_(entry_row(e), entry_col(e)) = 0.5 * j[e].lower() + 0.5 * j[e].upper();
  if (!jm_.allFinite()) return false;
  if (m == n) {
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(jm_);
    if (!regular(lu)) return block_precondition();
    operations_ += solve_operations();
    c_ = lu.inverse();
  } else {
    operations_ += solve_operations();
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(jm_);
    if (cod.rank() < n) return false;
    c_ = cod.pseudoInverse();
  }
  return c_.allFinite();
}

// C inverts each regular diagonal block of the midpoint Jacobian and is 0 on the others:
// Gauss-Seidel then narrows the regular blocks' unknowns and leaves the others (their rows
// of C F'(X) have 0 on the diagonal).
bool IntervalNewton::block_precondition() {
  if (blocks_.empty()) return false;
  const int n = unknowns();
  c_.setZero(n, n);
  bool any = false;
  double inverses = 0;
  for (const Block& b : blocks_) {
    const int size = static_cast<int>(b.cols.size());
    Eigen::MatrixXd a(size, size);
    for (int i = 0; i < size; ++i)
      for (int k = 0; k < size; ++k) a(i, k) = jm_(b.rows[i], b.cols[k]);
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(a);
    if (!regular(lu)) continue;
    const Eigen::MatrixXd inverse = lu.inverse();
    for (int k = 0; k < size; ++k)
      for (int i = 0; i < size; ++i) c_(b.cols[k], b.rows[i]) = inverse(k, i);
    inverses += std::floor(static_cast<double>(size) * size * size / 5);
    any = true;
  }
  // What solve_operations() counts, with these inverses for the whole one.
  const double whole = std::floor(static_cast<double>(n) * n * n / 5);
  if (any) operations_ += solve_operations() - whole + inverses;
  return any && c_.allFinite();
}

// Gauss-Seidel on C F'(X) (x - y) = -C F(y), x - y in X - y, over Newton's unknowns (the
// system's, or those left after substitution).
Outcome IntervalNewton::gauss_seidel(Box& box) {
  const bool substituted = !substitution_.empty();
  const int m = equations(), n = unknowns();
  const FastInterval* j = jacobian();
  const auto row = [&](int i) { return substituted ? substitution_.row(i) : i; };
  const auto col = [&](int k) { return substituted ? substitution_.col(k) : k; };

  // Only a row whose diagonal entry of C F'(X) excludes 0 can narrow anything (on a wide box,
  // often none): the others' rows of A and b are not built. Each entry sums its terms in the
  // order of the nonzeros, the same whichever rows are built.
  diagonal_.assign(n, FastInterval(0.0));
  for (int e = 0; e < nonzeros(); ++e)
    if (const double c = c_(entry_col(e), entry_row(e)); c != 0) diagonal_[entry_col(e)] += c * j[e];
  live_.clear();
  for (int i = 0; i < n; ++i)
    if (diagonal_[i].lower() > 0 || diagonal_[i].upper() < 0) live_.push_back(i);
  if (live_.empty()) return Outcome::unchanged;

  // A = C F'(X) (n x n) from the sparse Jacobian; b = -C F(y); live rows only.
  a_.assign(static_cast<size_t>(n) * n, FastInterval(0.0));
  for (int e = 0; e < nonzeros(); ++e) {
    const int r = entry_row(e), k = entry_col(e);
    for (int i : live_)
      if (const double c = c_(i, r); c != 0) a_[static_cast<size_t>(i) * n + k] += c * j[e];
  }
  b_.assign(n, FastInterval(0.0));
  for (int i : live_)
    for (int r = 0; r < m; ++r)
      if (const double c = c_(i, r); c != 0) b_[i] -= c * f_[row(r)];

  // Each row uses the rows narrowed before it.
  d_.resize(n);
  for (int i = 0; i < n; ++i) d_[i] = FastInterval(box[col(i)].lower(), box[col(i)].upper()) - y_[i];
  bool interior = true;
  size_t next_live = 0;
  for (int i = 0; i < n; ++i) {
    if (next_live == live_.size() || live_[next_live] != i) {  // its diagonal contains 0 (or NaN)
      interior = false;
      continue;
    }
    ++next_live;
    const FastInterval& aii = a_[static_cast<size_t>(i) * n + i];
    FastInterval s = b_[i];
    for (int k = 0; k < n; ++k)
      if (k != i) s -= a_[static_cast<size_t>(i) * n + k] * d_[k];
    const FastInterval ni = s / aii;
    const FastInterval moved = y_[i] + ni;
    interior = interior && box[col(i)].lower() < moved.lower() && moved.upper() < box[col(i)].upper();
    // NaN bounds of ni drop out of max/min: nothing is narrowed on them.
    const double lo = std::max(d_[i].lower(), ni.lower()), hi = std::min(d_[i].upper(), ni.upper());
    if (!(lo <= hi)) return Outcome::empty;
    d_[i] = FastInterval(lo, hi);
  }
  unique_ = interior;

  bool shrunk = false;
  for (int i = 0; i < n; ++i) {
    Interval& xi = box[col(i)];
    const FastInterval x = y_[i] + d_[i];
    const double lo = std::max(xi.lower(), x.lower()), hi = std::min(xi.upper(), x.upper());
    if (!(lo <= hi)) return Outcome::empty;
    if (lo != xi.lower() || hi != xi.upper()) {
      xi = Interval(lo, hi);
      shrunk = true;
    }
  }
  return shrunk ? Outcome::shrunk : Outcome::unchanged;
}

}  // namespace linkbox::prune
