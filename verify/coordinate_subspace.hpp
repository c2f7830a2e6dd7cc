#pragma once
// Curves of structurally redundant systems whose surplus equations vanish on a coordinate
// hyperplane S = {x_k = 0} (a wrist at gimbal lock: two closure components carry the factor
// t_2). On S, `vanishing` is identically zero (every term holds x_k: its other coefficients
// are exact zeros, so this is exact) and `rest` (n - 2 equations) is a curve system in the
// n - 1 other unknowns.
//
// Why an arc is then one of the whole system: let the kept equations be `rest` and one of
// `vanishing`, with an arc certificate over a box B (a graph over side p != k: for each t in
// B[p] exactly one root in B). If `rest` restricted to S also has an arc over B without side k,
// for the same side p (for each t one root z(t) on S inside B), then each z(t) solves every
// equation (the vanishing ones are zero on S), so it is a root of the kept equations and is
// the arc's point at t. So the whole arc consists of solutions, and since every solution in B
// solves the kept equations, the system's solution set in B is exactly that arc.
#include "model/compiled.hpp"
#include "newton/arc.hpp"

#include <memory>
#include <optional>
#include <vector>

namespace linkbox::verify {

struct CoordinateSubspace {
  int variable = -1;                 // k
  std::vector<int> vanishing;        // equations zero on x_k = 0
  std::vector<int> rest;             // the n - 2 others
  std::shared_ptr<const model::CompiledSystem> restricted;  // rest at x_k = 0, side k removed
  std::vector<model::Polynomial> slopes;  // d/dx_k of each vanishing equation
};

// The hyperplane of the first variable on which all but n - 2 of the equations vanish, when
// there are more than n - 1 equations; none otherwise.
std::optional<CoordinateSubspace> coordinate_subspace(const std::vector<model::Polynomial>& equations, size_t n);

// The equations an arc keeps when it keeps `vanishing[v]` of the surplus: all but the others.
std::vector<int> dropped_for(const CoordinateSubspace& s, size_t v);

// The v to try in turn at `point`: steepest across the hyperplane first (a vanishing equation
// is a multiple of x_k, and where its other factor is 0 the kept equations are singular).
std::vector<size_t> keep_order(const CoordinateSubspace& s, const Box& point);

// Whether the rest's zero set on S reaches across box[parameter] inside `box` (the second
// half of the argument above); the test's matrix is computed from the box alone.
bool spans_on_subspace(const CoordinateSubspace& s, const Box& box, int parameter);

}  // namespace linkbox::verify
