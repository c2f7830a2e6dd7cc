#include "prune/lp/safe_bound.hpp"

#include "interval/interval.hpp"

#include <cmath>
#include <vector>

namespace linkbox::prune::lp {

double dual_lower_bound(const LinearProgram& program, std::span<const double> y,
                        std::span<const std::pair<int, double>> objective) {
  const int n = program.num_cols(), m = program.num_rows();
  // One rounding guard for the whole evaluation: FastInterval skips per-operation mode
  // switches (lib/README.md, "Decisions"). Nothing else runs while it lives.
  RoundingGuard guard;
  std::vector<FastInterval> reduced(n, FastInterval(0.0));
  for (auto& [col, coef] : objective) reduced[col] += FastInterval(coef);

  FastInterval total(0.0);
  for (int i = 0; i < m && i < static_cast<int>(y.size()); ++i) {
    double yi = y[i];
    if (!(yi != 0) || !std::isfinite(yi)) continue;  // zero, NaN or inf: drop the row
    double bound = yi > 0 ? program.row_lo[i] : program.row_hi[i];
    if (!std::isfinite(bound)) continue;  // that side of the row constrains nothing
    total += FastInterval(bound) * yi;
    auto idx = program.row_indices(i);
    auto val = program.row_values(i);
    for (size_t k = 0; k < idx.size(); ++k) reduced[idx[k]] -= FastInterval(val[k]) * yi;
  }
  for (int j = 0; j < n; ++j) {
    const FastInterval& d = reduced[j];
    if (d.lower() == 0 && d.upper() == 0) continue;
    double lo = program.col_lo[j], hi = program.col_hi[j];
    // Boost would form 0 * inf on an infinite side; the bound is useless there anyway.
    if (!std::isfinite(lo) || !std::isfinite(hi)) return -kInf;
    total += d * FastInterval(lo, hi);
  }
  double result = total.lower();
  return std::isnan(result) ? -kInf : result;
}

bool proves_infeasible(const LinearProgram& program, std::span<const double> y) {
  return dual_lower_bound(program, y, {}) > 0;
}

}  // namespace linkbox::prune::lp
