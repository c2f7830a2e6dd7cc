#pragma once
// A box is one interval per variable of a system, in the system's variable order.
#include "interval/interval.hpp"

#include <span>
#include <string>
#include <vector>

namespace linkbox {

using Box = std::vector<Interval>;

// Longest side over the given dimensions (all when `dims` is empty).
double max_width(const Box& box, std::span<const int> dims = {});

// Index of the widest dimension among `dims` (all when empty); ties go to the lowest index.
int widest_dimension(const Box& box, std::span<const int> dims = {});

// Volume of `after` relative to `before`, over `dims`, as a product of per-side ratios so it
// neither underflows nor overflows with many dimensions. Zero-width sides count as ratio 1.
double volume_ratio(const Box& before, const Box& after, std::span<const int> dims = {});

// The point box of the sides' midpoints (median's values).
Box centre_box(const Box& box);

// Splits dimension `dim` at its midpoint.
std::pair<Box, Box> bisect(const Box& box, int dim);

// Hull of two boxes of the same dimension.
Box hull(const Box& a, const Box& b);

bool overlaps(const Box& a, const Box& b);  // closures touch or overlap
bool contains(const Box& outer, const Box& inner);

std::string to_string(const Box& box);

}  // namespace linkbox
