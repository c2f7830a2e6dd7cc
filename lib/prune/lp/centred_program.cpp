#include "prune/lp/centred_program.hpp"

#include "interval/interval.hpp"

#include <algorithm>
#include <cmath>

namespace linkbox::prune::lp {

LinearProgram centre_columns(const LinearProgram& lp, Centring& centring) {
  const int n = lp.num_cols();
  centring.shift.assign(n, 0.0);
  centring.scale.assign(n, 1.0);
  LinearProgram out;
  for (int j = 0; j < n; ++j) {
    const double lo = lp.col_lo[j], hi = lp.col_hi[j];
    if (std::isfinite(lo) && std::isfinite(hi) && lo < hi) {
      centring.shift[j] = 0.5 * lo + 0.5 * hi;  // halves first: no overflow
      centring.scale[j] = 0.5 * hi - 0.5 * lo;
    } else if (std::isfinite(lo) && lo == hi) {
      centring.shift[j] = lo;  // fixed column: u in [0, 0]
    }
    out.add_column(centring.to_u(j, lo), centring.to_u(j, hi));
    if (centring.scale[j] != 1.0) out.col_lo[j] = -1, out.col_hi[j] = 1;
  }
  // The centred rows are widened by the rounding of their offsets and coefficients, so that
  // they contain the original rows exactly: CLP must not see an infeasibility that rounding
  // made, least of all after a row is scaled up by 2^40.
  std::vector<std::pair<int, double>> row;
  centring.row_scale.assign(lp.num_rows(), 1.0);
  for (int r = 0; r < lp.num_rows(); ++r) {
    auto idx = lp.row_indices(r);
    auto val = lp.row_values(r);
    row.clear();
    Interval offset(0.0), slack(0.0);
    double largest = 0;
    for (size_t k = 0; k < idx.size(); ++k) {
      const int j = idx[k];
      if (centring.shift[j] != 0) offset += Interval(val[k]) * centring.shift[j];
      const double c = val[k] * centring.scale[j];
      if (centring.scale[j] != 1.0) slack += (Interval(val[k]) * centring.scale[j] - c) * Interval(-1.0, 1.0);
      row.push_back({j, c});
      largest = std::max(largest, std::fabs(c));
    }
    // An overflowing offset would give CLP NaN bounds; a free row just contributes no dual.
    if (!is_finite(offset) || !is_finite(slack)) {
      out.add_row(row, -INFINITY, INFINITY);
      continue;
    }
    const Interval shifted = slack - offset;
    const double lo = std::isfinite(lp.row_lo[r]) ? (lp.row_lo[r] + shifted).lower() : -INFINITY;
    const double hi = std::isfinite(lp.row_hi[r]) ? (lp.row_hi[r] + shifted).upper() : INFINITY;
    double r_scale = 1.0;
    if (largest > 0 && std::isfinite(largest)) r_scale = std::ldexp(1.0, -std::ilogb(largest));
    for (auto& term : row) term.second *= r_scale;
    centring.row_scale[r] = r_scale;
    out.add_row(row, lo * r_scale, hi * r_scale);
  }
  return out;
}

void to_original_rows(const Centring& centring, std::vector<double>& y) {
  for (size_t i = 0; i < y.size() && i < centring.row_scale.size(); ++i) y[i] *= centring.row_scale[i];
}

}  // namespace linkbox::prune::lp
