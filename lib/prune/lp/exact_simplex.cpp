#include "prune/lp/exact_simplex.hpp"

#include "interval/interval.hpp"
#include "prune/lp/dyadic.hpp"
#include "prune/lp/exact_simplex_data.hpp"
#include "prune/lp/exact_simplex_run.hpp"

#include <gmpxx.h>

#include <algorithm>
#include <cmath>

namespace linkbox::prune::lp {

void ExactSimplex::Data::set_row_bounds() {
  RoundingGuard guard;  // FastInterval rounds outward only inside it
  for (int i = 0; i < m; ++i) {
    double lo_i = row_lo[i], hi_i = row_hi[i];
    if (lo_i == -kInf || hi_i == kInf) {
      FastInterval range(0.0);
      for (int e = row_start[i]; e < row_start[i + 1]; ++e) {
        const int j = index[e];
        if (!std::isfinite(lo[j]) || !std::isfinite(hi[j])) {
          range = FastInterval(-kInf, kInf);
          break;
        }
        range += FastInterval(value[e]) * FastInterval(lo[j], hi[j]);
      }
      if (lo_i == -kInf && std::isfinite(range.lower())) lo_i = std::min(range.lower(), hi_i);
      if (hi_i == kInf && std::isfinite(range.upper())) hi_i = std::max(range.upper(), lo_i);
    }
    lo[n + i] = lo_i, hi[n + i] = hi_i;
  }
  // Narrow: a row whose bounds are closer than a billionth of the range its activity
  // takes over the box (a linear equation with interval coefficients). Moving it to its
  // other bound barely moves the basic solution.
  narrow.assign(n + m, 0);
  for (int i = 0; i < m; ++i) {
    const double width = row_hi[i] - row_lo[i];
    double range = 0;
    for (int e = row_start[i]; e < row_start[i + 1]; ++e) range += std::fabs(value[e]) * (hi[index[e]] - lo[index[e]]);
    narrow[n + i] = std::isfinite(width) && width <= 1e-9 * range;
  }
  implied_stale = false;
}

ExactSimplex::ExactSimplex() : d_(std::make_unique<Data>()) {}
ExactSimplex::~ExactSimplex() = default;

void ExactSimplex::load(const LinearProgram& p) {
  Data& d = *d_;
  d.n = p.num_cols(), d.m = p.num_rows();
  d.row_start = p.row_start;
  d.index = p.index;
  d.value = p.value;
  d.scaled.resize(p.value.size());
  d.shift.assign(d.m, 0);
  for (int i = 0; i < d.m; ++i) {
    int s = 0;
    for (int e = d.row_start[i]; e < d.row_start[i + 1]; ++e) s = std::max(s, integer_shift(d.value[e]));
    d.shift[i] = s;
    for (int e = d.row_start[i]; e < d.row_start[i + 1]; ++e) set_scaled(d.scaled[e], d.value[e], s);
  }
  d.lo.resize(d.n + d.m), d.hi.resize(d.n + d.m);
  for (int j = 0; j < d.n; ++j) d.lo[j] = p.col_lo[j], d.hi[j] = p.col_hi[j];
  d.row_lo = p.row_lo;
  d.row_hi = p.row_hi;
  d.implied_stale = true;
  d.lu.resize(d.n);
}

void ExactSimplex::set_column_bounds(int col, double lo, double hi) {
  Data& d = *d_;
  // Narrowing keeps the implied row bounds implied; widening does not.
  if (!(lo >= d.lo[col] && hi <= d.hi[col])) d.implied_stale = true;
  d.lo[col] = lo;
  d.hi[col] = hi;
}

bool ExactSimplex::proves_infeasible(std::span<const double> y) const {
  // The implied row bounds below must be those of the current column box: after a load (or
  // a widening) they still belong to the previous box until refreshed.
  if (d_->implied_stale) d_->set_row_bounds();
  const Data& d = *d_;
  // For every feasible x, y_i (a_i . x) >= y_i * (the row bound y_i's sign selects); summed,
  // (A^T y) . x >= beta. No x of the box reaches beta: infeasible. Rare (only on CLP's
  // infeasibility verdicts), so plain rationals.
  std::vector<mpq_class> g(d.n);
  mpq_class beta = 0, yi, t;
  bool any = false;
  for (int i = 0; i < d.m && i < static_cast<int>(y.size()); ++i) {
    if (!(y[i] != 0) || !std::isfinite(y[i])) continue;
    const int v = d.n + i;
    const bool positive = y[i] > 0;
    const double bound = positive ? d.lo[v] : d.hi[v];
    if (!std::isfinite(bound)) continue;
    yi = y[i];
    any = true;
    beta += yi * mpq_class(bound);
    for (int k = d.row_start[i]; k < d.row_start[i + 1]; ++k) {
      t = d.value[k];
      g[d.index[k]] += yi * t;
    }
  }
  if (!any) return false;
  mpq_class top = 0;  // max of g . x over the box
  for (int j = 0; j < d.n; ++j) {
    const int s = sgn(g[j]);
    if (s == 0) continue;
    const double bound = s > 0 ? d.hi[j] : d.lo[j];
    if (!std::isfinite(bound)) return false;  // unbounded above
    top += g[j] * mpq_class(bound);
  }
  return top < beta;
}

ExactSimplex::Result ExactSimplex::solve(int col, double sense, std::vector<BasisStatus> cols, std::vector<BasisStatus> rows,
                                         int max_pivots) {
  Data& d = *d_;
  if (d.implied_stale) d.set_row_bounds();
  Run run(d, col, sense, max_pivots);
  return run.solve(cols, rows);
}

}  // namespace linkbox::prune::lp
