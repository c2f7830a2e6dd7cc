#include "model/block_triangular.hpp"

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/max_cardinality_matching.hpp>
#include <boost/graph/strong_components.hpp>

#include <algorithm>
#include <numeric>

namespace linkbox::model {

namespace {

// A maximum matching of columns (vertices 0..cols-1) to rows (cols..cols+rows-1).
std::vector<int> matched_rows(int rows, int cols, const std::vector<std::pair<int, int>>& entries) {
  using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS>;
  Graph g(cols + rows);
  for (auto [r, k] : entries) boost::add_edge(k, cols + r, g);
  std::vector<Graph::vertex_descriptor> mate(cols + rows);
  boost::edmonds_maximum_cardinality_matching(g, &mate[0]);
  std::vector<int> row_of(cols, -1);
  for (int k = 0; k < cols; ++k)
    if (mate[k] != Graph::null_vertex()) row_of[k] = static_cast<int>(mate[k]) - cols;
  return row_of;
}

}  // namespace

BlockTriangular block_triangular(int rows, int cols, const std::vector<std::pair<int, int>>& entries) {
  const std::vector<int> row_of = matched_rows(rows, cols, entries);
  std::vector<std::vector<int>> in_row(rows);
  for (auto [r, k] : entries) in_row[r].push_back(k);
  // j -> k: unknown j's row involves k, so j's block comes after k's.
  using Digraph = boost::adjacency_list<boost::vecS, boost::vecS, boost::directedS>;
  Digraph g(cols);
  for (int j = 0; j < cols; ++j)
    if (row_of[j] >= 0)
      for (int k : in_row[row_of[j]])
        if (k != j) boost::add_edge(j, k, g);
  // Tarjan numbers a component once every component it reaches is numbered: upstream first.
  std::vector<int> component(cols);
  boost::strong_components(g, &component[0]);
  BlockTriangular r{std::vector<int>(cols), std::vector<int>(cols), row_of};
  r.square = std::all_of(row_of.begin(), row_of.end(), [](int row) { return row >= 0; });
  std::vector<bool> seen(cols, false);
  for (int k = 0; k < cols; ++k) {
    r.block[k] = row_of[k] < 0 ? cols : component[k];
    if (row_of[k] >= 0 && !seen[component[k]]) seen[component[k]] = true, ++r.blocks;
  }
  std::iota(r.order.begin(), r.order.end(), 0);
  std::stable_sort(r.order.begin(), r.order.end(), [&](int a, int b) { return r.block[a] < r.block[b]; });
  return r;
}

}  // namespace linkbox::model
