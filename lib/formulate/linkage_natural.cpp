// LinkageFormulation's certification charts: the loop closure in joint variables.
#include "formulate/half_angle.hpp"
#include "formulate/linkage.hpp"
#include "formulate/loop_closure.hpp"

namespace linkbox::formulate {

namespace {
// The natural unknowns are the outputs of a single loop, entry by entry.
bool single_loop(const LinkageCase& c) { return c.loops.size() == 1 && c.angle_constraints.empty(); }

std::uint64_t revolute_mask(const LinkageLoop& loop) {
  std::uint64_t m = 0;
  for (size_t i = 0; i < loop.links.size(); ++i)
    if (!loop.links[i].prismatic) m |= std::uint64_t{1} << i;
  return m;
}
}  // namespace

std::uint64_t LinkageFormulation::chart_for(const Box& output_hull) const {
  if (!single_loop(case_)) return 0;
  return half_turn_chart(output_hull) & revolute_mask(case_.loops[0]);
}

NaturalSystem LinkageFormulation::natural_system(std::uint64_t chart) const {
  if (!single_loop(case_)) return {};
  const LinkageLoop& loop = case_.loops[0];
  NaturalSystem s;
  std::vector<int> variable;
  for (size_t i = 0; i < loop.links.size(); ++i) {
    variable.push_back(static_cast<int>(i));
    s.unknowns.push_back(loop.links[i].prismatic ? loop.links[i].joint : "t_" + loop.links[i].joint);
  }
  s.equations = dh_loop_closure(loop, variable, chart);
  if (has_prismatic_) {
    // Offsets count within their ranges; tangents are unbounded (charts cover the circle).
    for (auto& l : loop.links) s.domain.push_back(l.prismatic ? l.d : Interval(-1e300, 1e300));
  }
  return s;
}

namespace {
// Maps the revolute entries through a chart function; prismatic offsets stay as they are.
template <class Map>
Box on_revolute(const LinkageLoop& loop, const Box& b, Map map) {
  const std::uint64_t revolute = revolute_mask(loop);
  const Box mapped = map(b);
  Box out = b;
  for (size_t i = 0; i < out.size(); ++i)
    if (revolute >> i & 1) out[i] = mapped[i];
  return out;
}
}  // namespace

Box LinkageFormulation::output_to_natural(std::uint64_t chart, const Box& output) const {
  if (!single_loop(case_)) return output;
  return on_revolute(case_.loops[0], output, [&](const Box& b) { return angles_to_tangents(chart, b); });
}

Box LinkageFormulation::natural_to_output(std::uint64_t chart, const Box& natural) const {
  if (!single_loop(case_)) return natural;
  return on_revolute(case_.loops[0], natural, [&](const Box& b) { return tangents_to_angles(chart, b); });
}

}  // namespace linkbox::formulate
