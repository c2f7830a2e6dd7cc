#pragma once
// The LP data every backend reads: columns with bounds (the box) and sparse rows
// row_lo <= sum a_j x_j <= row_hi with double coefficients. The coefficients are exact
// rationals as far as the backends are concerned; soundness of a relaxation is decided when
// the rows are built (outward-rounded right-hand sides), not here.
#include <initializer_list>
#include <span>
#include <utility>
#include <vector>

namespace linkbox::prune::lp {

struct LinearProgram {
  // Columns. Bounds should be finite: an infinite bound makes the rigorous (N-S) bound
  // trivial whenever the float dual leaves a non-zero reduced cost on that column.
  std::vector<double> col_lo, col_hi;

  // Rows in compressed sparse row form; row r holds entries [row_start[r], row_start[r+1]).
  std::vector<int> row_start{0};
  std::vector<int> index;
  std::vector<double> value;
  std::vector<double> row_lo, row_hi;  // either may be -inf / +inf

  int num_cols() const { return static_cast<int>(col_lo.size()); }
  int num_rows() const { return static_cast<int>(row_lo.size()); }

  int add_column(double lo, double hi);
  // Adds lo <= sum coef * x[col] <= hi; zero coefficients are dropped, a repeated column
  // throws std::invalid_argument. Returns the row index.
  int add_row(std::span<const std::pair<int, double>> terms, double lo, double hi);
  int add_row(std::initializer_list<std::pair<int, double>> terms, double lo, double hi) {
    return add_row(std::span<const std::pair<int, double>>(terms.begin(), terms.size()), lo, hi);
  }

  std::span<const int> row_indices(int r) const {
    return {index.data() + row_start[r], index.data() + row_start[r + 1]};
  }
  std::span<const double> row_values(int r) const {
    return {value.data() + row_start[r], value.data() + row_start[r + 1]};
  }

  void clear();
};

}  // namespace linkbox::prune::lp
