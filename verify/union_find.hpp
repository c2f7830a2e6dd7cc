#pragma once
// Disjoint sets over 0..n-1 (union by size, path halving): near-linear clustering.
#include <numeric>
#include <vector>

namespace linkbox::verify {

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(n), size_(n, 1) { std::iota(parent_.begin(), parent_.end(), 0); }

  int find(int x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }

  // Returns false when a and b were already joined.
  bool unite(int a, int b) {
    a = find(a), b = find(b);
    if (a == b) return false;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
    return true;
  }

  // The sets, each sorted ascending, ordered by their smallest member: independent of the
  // order in which unions happened.
  std::vector<std::vector<int>> groups() {
    std::vector<int> slot(parent_.size(), -1);
    std::vector<std::vector<int>> out;
    for (int i = 0; i < static_cast<int>(parent_.size()); ++i) {
      int r = find(i);
      if (slot[r] < 0) slot[r] = static_cast<int>(out.size()), out.emplace_back();
      out[slot[r]].push_back(i);
    }
    return out;
  }

 private:
  std::vector<int> parent_, size_;
};

}  // namespace linkbox::verify
