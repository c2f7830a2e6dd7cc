#include "prune/lp/centred_program.hpp"

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
  std::vector<std::pair<int, double>> row;
  for (int r = 0; r < lp.num_rows(); ++r) {
    auto idx = lp.row_indices(r);
    auto val = lp.row_values(r);
    row.clear();
    double offset = 0;
    for (size_t k = 0; k < idx.size(); ++k) {
      offset += val[k] * centring.shift[idx[k]];
      row.push_back({idx[k], val[k] * centring.scale[idx[k]]});
    }
    // An overflowing offset would give CLP NaN bounds; a free row just contributes no dual.
    if (!std::isfinite(offset)) out.add_row(row, -INFINITY, INFINITY);
    else out.add_row(row, lp.row_lo[r] - offset, lp.row_hi[r] - offset);
  }
  return out;
}

}  // namespace linkbox::prune::lp
