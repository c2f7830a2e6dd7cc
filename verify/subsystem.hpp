#pragma once
// Picking equations out of a system by index.
#include "model/polynomial.hpp"

#include <algorithm>
#include <vector>

namespace linkbox::verify {

// 0..count-1 without those in `left_out`.
inline std::vector<int> rows_except(size_t count, const std::vector<int>& left_out) {
  std::vector<int> rows;
  for (int r = 0; r < static_cast<int>(count); ++r)
    if (std::find(left_out.begin(), left_out.end(), r) == left_out.end()) rows.push_back(r);
  return rows;
}

inline std::vector<model::Polynomial> pick(const std::vector<model::Polynomial>& f, const std::vector<int>& rows) {
  std::vector<model::Polynomial> out;
  for (int r : rows) out.push_back(f[r]);
  return out;
}

}  // namespace linkbox::verify
