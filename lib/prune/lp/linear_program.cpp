#include "prune/lp/linear_program.hpp"

#include <algorithm>
#include <stdexcept>

namespace linkbox::prune::lp {

int LinearProgram::add_column(double lo, double hi) {
  col_lo.push_back(lo);
  col_hi.push_back(hi);
  return num_cols() - 1;
}

int LinearProgram::add_row(std::span<const std::pair<int, double>> terms, double lo, double hi) {
  // A repeated column would have to be summed in floating point, silently changing the
  // row a caller proved sound; callers merge repeats themselves (in interval arithmetic).
  std::vector<std::pair<int, double>> sorted(terms.begin(), terms.end());
  std::sort(sorted.begin(), sorted.end(), [](auto& a, auto& b) { return a.first < b.first; });
  for (size_t k = 0; k < sorted.size(); ++k) {
    int col = sorted[k].first;
    if (col < 0 || col >= num_cols()) throw std::out_of_range("LinearProgram::add_row: bad column");
    if (k > 0 && sorted[k - 1].first == col)
      throw std::invalid_argument("LinearProgram::add_row: repeated column");
  }
  for (auto& [col, coef] : sorted) {
    if (coef == 0) continue;
    index.push_back(col);
    value.push_back(coef);
  }
  row_start.push_back(static_cast<int>(index.size()));
  row_lo.push_back(lo);
  row_hi.push_back(hi);
  return num_rows() - 1;
}

void LinearProgram::clear() {
  col_lo.clear();
  col_hi.clear();
  row_start.assign(1, 0);
  index.clear();
  value.clear();
  row_lo.clear();
  row_hi.clear();
}

}  // namespace linkbox::prune::lp
