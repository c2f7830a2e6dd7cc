// Clustering of solution boxes: the sweep must give exactly the partition of the all-pairs
// touch relation, also across the +pi/-pi seam of angle dimensions, and stay fast.
#include "verify/cluster.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <numeric>
#include <random>

using linkbox::Box;
using linkbox::Interval;
using namespace linkbox::verify;

namespace {

const double kPi = M_PI;  // the double just below pi

// Reference: every pair, with its own tiny union-find.
std::vector<std::vector<int>> brute_force(const std::vector<Box>& boxes, const std::vector<bool>& periodic) {
  std::vector<int> parent(boxes.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x];
    return x;
  };
  for (size_t i = 0; i < boxes.size(); ++i)
    for (size_t j = i + 1; j < boxes.size(); ++j)
      if (boxes_touch(boxes[i], boxes[j], periodic)) parent[find(j)] = find(i);
  std::vector<std::vector<int>> out;
  std::vector<int> slot(boxes.size(), -1);
  for (size_t i = 0; i < boxes.size(); ++i) {
    int r = find(static_cast<int>(i));
    if (slot[r] < 0) slot[r] = static_cast<int>(out.size()), out.emplace_back();
    out[slot[r]].push_back(static_cast<int>(i));
  }
  return out;
}

// Random boxes on a coarse dyadic grid so that many share faces or corners exactly, some of
// them ending exactly at +-pi (as doubles) or shifted by a whole turn.
std::vector<Box> random_boxes(int n, int dim, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> cell(-50, 49), span(1, 3), kind(0, 9), turn(-1, 1);
  std::vector<Box> boxes;
  for (int i = 0; i < n; ++i) {
    Box b;
    for (int d = 0; d < dim; ++d) {
      double lo = cell(rng) / 16.0, hi = lo + span(rng) / 16.0;
      int k = kind(rng);
      if (k == 0) lo = kPi - span(rng) / 16.0, hi = kPi;
      if (k == 1) lo = -kPi, hi = -kPi + span(rng) / 16.0;
      Interval x(lo, hi);
      if (k == 2) x = x + Interval(turn(rng)) * two_pi();  // same arc, another turn
      b.push_back(x);
    }
    boxes.push_back(b);
  }
  return boxes;
}

}  // namespace

TEST_CASE("boxes_touch: faces, corners and gaps", "[cluster]") {
  Box a{{0, 1}, {0, 1}}, face{{1, 2}, {0.5, 3}}, corner{{1, 2}, {1, 2}}, gap{{1.0000001, 2}, {0, 1}};
  CHECK(boxes_touch(a, face));
  CHECK(boxes_touch(a, corner));
  CHECK_FALSE(boxes_touch(a, gap));
  CHECK_FALSE(boxes_touch(a, Box{{std::nan(""), 1}, {0, 1}}));
}

TEST_CASE("boxes_touch: periodic dimensions wrap at +-pi", "[cluster]") {
  Box near_plus{{kPi - 0.01, kPi}, {0, 1}}, near_minus{{-kPi, -kPi + 0.01}, {0.5, 2}};
  CHECK_FALSE(boxes_touch(near_plus, near_minus));
  CHECK(boxes_touch(near_plus, near_minus, {true, false}));
  CHECK_FALSE(boxes_touch(near_plus, near_minus, {false, true}));
  // 3.1 and -3.1 are 2*pi - 6.2 ~ 0.083 apart around the circle.
  CHECK_FALSE(boxes_touch(Box{{3.0, 3.1}}, Box{{-3.1, -3.0}}, {true}));
  // Whole turns away, and arcs that together cover the circle.
  CHECK(boxes_touch(Box{{0.5, 0.6}}, Box{{0.6 + 4 * kPi, 0.7 + 4 * kPi}}, {true}));
  CHECK(boxes_touch(Box{{0, 3.2}}, Box{{3.3, 6.4}}, {true}));         // wraps past 2*pi
  CHECK_FALSE(boxes_touch(Box{{0.1, 3.2}}, Box{{3.3, 6.35}}, {true}));  // gaps on both sides
  CHECK(boxes_touch(Box{{0, 1}}, Box{{-linkbox::kInf, -5}}, {true}));
}

TEST_CASE("cluster_boxes matches all-pairs union-find", "[cluster]") {
  auto periodic = GENERATE(std::vector<bool>{}, std::vector<bool>{true, false, true},
                           std::vector<bool>{true, true, true});
  for (unsigned seed = 1; seed <= 6; ++seed) {
    auto boxes = random_boxes(1500, 3, seed);
    auto fast = cluster_boxes(boxes, periodic);
    CHECK(fast == brute_force(boxes, periodic));
  }
}

TEST_CASE("cluster_boxes: deterministic order and edge cases", "[cluster]") {
  std::vector<Box> boxes{{{5, 6}}, {{0, 1}}, {{6, 7}}, {{1, 2}}, {{10, 11}}};
  auto c = cluster_boxes(boxes);
  CHECK(c == std::vector<std::vector<int>>{{0, 2}, {1, 3}, {4}});
  CHECK(cluster_boxes({}).empty());
  CHECK_THROWS_AS(cluster_boxes({Box{{0, 1}}, Box{{0, 1}, {0, 1}}}), std::invalid_argument);
  CHECK_THROWS_AS(cluster_boxes({Box{{0, 1}}}, {true, false}), std::invalid_argument);
}

TEST_CASE("cluster_boxes: 100k tiny boxes quickly", "[cluster]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3, 3);
  std::vector<Box> scattered, chain;
  for (int i = 0; i < 100000; ++i) {
    double x = u(rng), y = u(rng), z = u(rng);
    scattered.push_back({{x, x + 1e-6}, {y, y + 1e-6}, {z, z + 1e-6}});
  }
  // One curve winding twice around the angle seam, in shuffled order: one cluster.
  const int m = 100000;
  std::vector<int> perm(m);
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  for (int k : perm) {
    double t0 = -kPi + 4 * kPi * k / m, t1 = -kPi + 4 * kPi * (k + 1) / m;
    chain.push_back({{std::remainder(t0, 2 * kPi), std::remainder(t0, 2 * kPi) + (t1 - t0) * 1.01},
                     {0.5 + 1e-5 * k, 0.5 + 1e-5 * (k + 1)}});
  }
  auto start = std::chrono::steady_clock::now();
  auto a = cluster_boxes(scattered);
  auto b = cluster_boxes(chain, {true, false});
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(a.size() > 99000);
  CHECK(b.size() == 1);
  CHECK(seconds < 5.0);
}
