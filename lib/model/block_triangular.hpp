#pragma once
// The block-triangular order of a sparse system's unknowns (Dulmage-Mendelsohn's fine
// decomposition): each row matched to an unknown it involves, then the strongly connected
// components of "the row of unknown j involves unknown k". In this order each block's rows
// involve only its own unknowns and those of blocks before it, so a Gauss-Seidel sweep that
// follows it narrows a block after everything that block depends on.
#include <utility>
#include <vector>

namespace linkbox::model {

struct BlockTriangular {
  std::vector<int> order;  // the columns 0..cols-1, upstream blocks first, each in increasing order
  std::vector<int> block;  // per column: its block's place in that order (unmatched columns: last)
  std::vector<int> row;    // per column: the row matched to it, -1 for none
  int blocks = 0;          // how many, unmatched columns not counted
  bool square = false;     // every column matched (no curve's free direction)
};

// `entries`: the (row, column) pairs of the nonzero pattern.
BlockTriangular block_triangular(int rows, int cols, const std::vector<std::pair<int, int>>& entries);

// Those pairs of a sparse Jacobian with nonzeros(), entry_row(e) and entry_col(e).
template <class Sparse>
std::vector<std::pair<int, int>> pattern_of(const Sparse& s) {
  std::vector<std::pair<int, int>> entries;
  for (int e = 0; e < s.nonzeros(); ++e) entries.emplace_back(s.entry_row(e), s.entry_col(e));
  return entries;
}

}  // namespace linkbox::model
