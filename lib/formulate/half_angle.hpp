#pragma once
// Charts of half-angle tangents: t = tan((phi - s*pi)/2) with s in {0, 1} per angle, so
// that every angle has a chart where |phi - s*pi| <= pi/2 and t stays in [-1, 1].
#include "interval/box.hpp"

#include <cstdint>

namespace linkbox::formulate {

// `angles` marks the dimensions that are angles (bit j: dimension j); the others, e.g.
// prismatic offsets, are copied as they are and never shifted. Dimensions from 64 on are
// angles.
constexpr std::uint64_t all_angles = ~std::uint64_t{0};

// Shift mask whose charts put every angle's midpoint within pi/2 (+ slack) of s*pi.
std::uint64_t half_turn_chart(const Box& angles, std::uint64_t is_angle = all_angles);
// Rigorous t-box of angles in the chart; throws std::domain_error if an angle interval is
// too wide (meets the chart's pole at phi = s*pi + pi).
Box angles_to_tangents(std::uint64_t chart, const Box& angles, std::uint64_t is_angle = all_angles);
// Rigorous angles phi = 2 atan(t) + s*pi, reported in (-pi, pi] where the whole interval
// allows (an interval across pi stays as it is).
Box tangents_to_angles(std::uint64_t chart, const Box& tangents, std::uint64_t is_angle = all_angles);

}  // namespace linkbox::formulate
