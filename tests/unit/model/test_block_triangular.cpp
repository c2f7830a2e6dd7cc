// The block-triangular order (model/block_triangular.hpp): on a pattern with known blocks it
// finds them in dependency order, and on random permuted patterns every matched row involves
// only its own block and blocks before it.
#include "model/block_triangular.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <numeric>
#include <random>

using namespace linkbox;

TEST_CASE("a pattern with three blocks is ordered upstream first", "[block-triangular]") {
  // Row 0 holds x2 alone; rows 1 and 2 couple x0 and x1 (and read x2); row 3 reads x0 and x3.
  const std::vector<std::pair<int, int>> entries{{0, 2}, {1, 0}, {1, 1}, {1, 2}, {2, 0}, {2, 1}, {3, 3}, {3, 0}};
  const model::BlockTriangular b = model::block_triangular(4, 4, entries);
  CHECK(b.square);
  CHECK(b.blocks == 3);
  CHECK(b.order == std::vector<int>{2, 0, 1, 3});
  CHECK(b.block[0] == b.block[1]);
  CHECK(b.block[2] < b.block[0]);
  CHECK(b.block[0] < b.block[3]);
  CHECK(b.row[2] == 0);
  CHECK(b.row[3] == 3);
}

TEST_CASE("a curve's pattern leaves a column unmatched and is not square", "[block-triangular]") {
  const model::BlockTriangular b = model::block_triangular(1, 2, {{0, 0}, {0, 1}});
  CHECK_FALSE(b.square);
  CHECK(b.blocks == 1);
  CHECK(std::count(b.row.begin(), b.row.end(), -1) == 1);
}

TEST_CASE("random block-triangular patterns: each row reads only its block and earlier ones",
          "[block-triangular]") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 2 + static_cast<int>(rng() % 12);
    // Planted blocks of sizes 1-3, each row reading its own block densely and earlier
    // columns at random; then rows and columns shuffled.
    std::vector<int> planted_block(n);
    for (int k = 0, b = 0; k < n; ++b)
      for (int size = 1 + static_cast<int>(rng() % 3); size > 0 && k < n; --size) planted_block[k++] = b;
    std::vector<int> rows(n), cols(n);
    std::iota(rows.begin(), rows.end(), 0);
    std::iota(cols.begin(), cols.end(), 0);
    std::shuffle(rows.begin(), rows.end(), rng);
    std::shuffle(cols.begin(), cols.end(), rng);
    std::vector<std::pair<int, int>> entries;
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < n; ++k)
        if (planted_block[k] == planted_block[i] || (planted_block[k] < planted_block[i] && rng() % 3 == 0))
          entries.emplace_back(rows[i], cols[k]);
    const model::BlockTriangular b = model::block_triangular(n, n, entries);
    REQUIRE(b.square);
    CHECK(b.blocks == planted_block.back() + 1);
    std::vector<int> column_of_row(n, -1);
    for (int k = 0; k < n; ++k) column_of_row[b.row[k]] = k;
    for (auto [r, k] : entries) CHECK(b.block[k] <= b.block[column_of_row[r]]);
    for (int i = 1; i < n; ++i) CHECK(b.block[b.order[i - 1]] <= b.block[b.order[i]]);
  }
}
