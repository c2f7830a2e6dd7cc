#include "formulate/half_angle.hpp"

#include "interval/rigorous.hpp"

#include <cmath>
#include <stdexcept>

namespace linkbox::formulate {

namespace {
bool angle_at(std::uint64_t is_angle, size_t j) { return j >= 64 || (is_angle >> j & 1); }
}  // namespace

std::uint64_t half_turn_chart(const Box& angles, std::uint64_t is_angle) {
  std::uint64_t chart = 0;
  for (size_t j = 0; j < angles.size(); ++j) {
    if (!angle_at(is_angle, j)) continue;
    // Distance of the midpoint from 0 modulo 2 pi: more than pi/2 -> the shifted chart.
    double m = std::remainder(median(angles[j]), 2 * M_PI);
    if (std::abs(m) > M_PI / 2 + 1e-9) chart |= std::uint64_t{1} << j;
  }
  return chart;
}

Box angles_to_tangents(std::uint64_t chart, const Box& angles, std::uint64_t is_angle) {
  const Interval pi = rigorous::pi(), two_pi = pi * Interval(2.0);
  Box t = angles;
  for (size_t j = 0; j < angles.size(); ++j) {
    if (!angle_at(is_angle, j)) continue;
    Interval a = angles[j];
    if (chart >> j & 1) a -= pi;
    // Bring the interval's midpoint into [-pi, pi] by whole turns (exact shift of the set).
    const double turns = std::round(median(a) / (2 * M_PI));
    if (turns != 0) a -= two_pi * Interval(turns);
    t[j] = rigorous::tan(a / Interval(2.0));
  }
  return t;
}

Box tangents_to_angles(std::uint64_t chart, const Box& t, std::uint64_t is_angle) {
  const Interval pi = rigorous::pi(), two_pi = pi * Interval(2.0);
  Box out = t;
  for (size_t j = 0; j < t.size(); ++j) {
    if (!angle_at(is_angle, j)) continue;
    out[j] = rigorous::angle_from_half_tangent(t[j], static_cast<int>(chart >> j & 1));
    if (out[j].lower() > pi.upper()) out[j] -= two_pi;
  }
  return out;
}

}  // namespace linkbox::formulate
