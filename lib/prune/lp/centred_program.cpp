#include "prune/lp/centred_program.hpp"

#include "interval/interval.hpp"

#include <algorithm>
#include <cmath>

namespace linkbox::prune::lp {

namespace {
// Row r's bounds in the centred columns, widened by the rounding of its offset and of its
// centred coefficients, inside a RoundingGuard. False where the offset overflows: it would
// give CLP NaN bounds, so the row is left free (it just contributes no dual).
bool row_bounds(const LinearProgram& lp, const Centring& centring, const std::vector<double>& coefficient, int r,
                double& lo, double& hi) {
  FastInterval offset(0.0), slack(0.0);
  for (int k = lp.row_start[r]; k < lp.row_start[r + 1]; ++k) {
    const int j = lp.index[k];
    if (centring.shift[j] != 0) offset += FastInterval(lp.value[k]) * centring.shift[j];
    if (centring.scale[j] != 1.0)
      slack += (FastInterval(lp.value[k]) * centring.scale[j] - coefficient[k]) * FastInterval(-1.0, 1.0);
  }
  lo = -INFINITY;
  hi = INFINITY;
  if (!std::isfinite(offset.lower()) || !std::isfinite(offset.upper()) || !std::isfinite(slack.lower()) ||
      !std::isfinite(slack.upper()))
    return false;
  const FastInterval shifted = slack - offset;
  if (std::isfinite(lp.row_lo[r])) lo = (lp.row_lo[r] + shifted).lower();
  if (std::isfinite(lp.row_hi[r])) hi = (lp.row_hi[r] + shifted).upper();
  return true;
}
}  // namespace

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
  // made, least of all after a row is scaled up by 2^40. The coefficients are rounded to
  // nearest here; the widening is then summed under one RoundingGuard, not in protected
  // operations that each switch the rounding mode.
  std::vector<double> coefficient(lp.value.size());
  for (size_t k = 0; k < lp.value.size(); ++k) coefficient[k] = lp.value[k] * centring.scale[lp.index[k]];
  std::vector<double> lo(lp.num_rows()), hi(lp.num_rows());
  std::vector<char> bounded(lp.num_rows());
  {
    RoundingGuard guard;
    for (int r = 0; r < lp.num_rows(); ++r) bounded[r] = row_bounds(lp, centring, coefficient, r, lo[r], hi[r]);
  }
  std::vector<std::pair<int, double>> row;
  centring.row_scale.assign(lp.num_rows(), 1.0);
  for (int r = 0; r < lp.num_rows(); ++r) {
    row.clear();
    double largest = 0;
    for (int k = lp.row_start[r]; k < lp.row_start[r + 1]; ++k) {
      row.push_back({lp.index[k], coefficient[k]});
      largest = std::max(largest, std::fabs(coefficient[k]));
    }
    if (!bounded[r]) {
      out.add_row(row, -INFINITY, INFINITY);
      continue;
    }
    double r_scale = 1.0;
    if (largest > 0 && std::isfinite(largest)) r_scale = std::ldexp(1.0, -std::ilogb(largest));
    for (auto& term : row) term.second *= r_scale;
    centring.row_scale[r] = r_scale;
    out.add_row(row, lo[r] * r_scale, hi[r] * r_scale);
  }
  return out;
}

void to_original_rows(const Centring& centring, std::vector<double>& y) {
  for (size_t i = 0; i < y.size() && i < centring.row_scale.size(); ++i) y[i] *= centring.row_scale[i];
}

}  // namespace linkbox::prune::lp
