#include "verify/twin_loops.hpp"

namespace linkbox::verify {

namespace {

using input::LinkageLoop;

using input::same_link;
using input::same_real;

// The one joint the two loops share, at the same entry of both; -1 when there is none such.
int shared_entry(const LinkageLoop& a, const LinkageLoop& b) {
  int entry = -1, shared = 0;
  for (size_t i = 0; i < a.links.size(); ++i)
    for (size_t j = 0; j < b.links.size(); ++j)
      if (a.links[i].joint == b.links[j].joint) {
        ++shared;
        entry = i == j ? static_cast<int>(i) : -1;
      }
  return shared == 1 ? entry : -1;
}

// The angle constraint between joints p and q, in either order; -1 when none or several.
int constraint_between(const input::LinkageCase& c, const std::string& p, const std::string& q) {
  int found = -1;
  for (size_t k = 0; k < c.angle_constraints.size(); ++k) {
    const auto& ac = c.angle_constraints[k];
    if ((ac.joint1 == p && ac.joint2 == q) || (ac.joint1 == q && ac.joint2 == p)) {
      if (found >= 0) return -1;
      found = static_cast<int>(k);
    }
  }
  return found;
}

bool shift_of(std::uint64_t chart, int k) { return k < 64 && (chart >> k & 1); }

// The loops' closures (loop_closure.hpp: a function of the links, their unknowns and the
// chart) are one real system up to renaming: the same links, each unknown pair in the same
// chart. Their interval enclosures may still differ by roundings (terms summed in another
// order), which is why the polynomials are not compared.
bool same_closures(const formulate::LinkageFormulation& f, std::uint64_t chart) {
  const auto& loops = f.linkage_case().loops;
  const std::vector<int>&u = f.loop_unknowns(0), &w = f.loop_unknowns(1);
  if (loops[0].links.size() != loops[1].links.size() || u.size() != loops[0].links.size() || w.size() != u.size())
    return false;
  for (size_t i = 0; i < u.size(); ++i)
    if (!same_link(loops[0].links[i], loops[1].links[i]) || shift_of(chart, u[i]) != shift_of(chart, w[i]))
      return false;
  return true;
}

}  // namespace

std::optional<TwinConstraint> twin_constraint(const formulate::LinkageFormulation& f, std::uint64_t chart,
                                              const std::vector<std::optional<RigidRoot>>& roots) {
  const input::LinkageCase& c = f.linkage_case();
  const formulate::NaturalSystem& sys = f.natural(chart);
  if (c.loops.size() != 2 || roots.size() != 2 || !roots[0] || !roots[1] || sys.loop_rows.size() != 2)
    return std::nullopt;
  const LinkageLoop &one = c.loops[0], &two = c.loops[1];
  const int n = static_cast<int>(one.links.size());
  const int e = shared_entry(one, two);
  if (e < 0 || n < 3 || one.links[e].prismatic || !same_closures(f, chart)) return std::nullopt;
  // The second loop's root is where the first's is unique: it is the first's, renamed.
  for (int i = 0; i < n; ++i)
    if (!subset(roots[1]->image[i], roots[0]->unique[i])) return std::nullopt;
  const int after = (e + 1) % n, before = (e + n - 1) % n;
  const int a = constraint_between(c, one.links[after].joint, two.links[after].joint);
  const int b = constraint_between(c, one.links[before].joint, two.links[before].joint);
  if (a < 0 || b < 0 || !same_real(c.angle_constraints[a].exact_angle, c.angle_constraints[b].exact_angle))
    return std::nullopt;
  const std::string &ta = one.links[e].exact.alpha, &tb = two.links[e].exact.alpha,
                    &ua = one.links[before].exact.alpha, &ub = two.links[before].exact.alpha;
  if (!((same_real(ta, ua) && same_real(tb, ub)) || (same_real(ta, ub) && same_real(tb, ua)))) return std::nullopt;
  TwinConstraint t;
  t.implied_row = sys.loop_rows[1].second + b;
  t.how = "loops '" + one.name + "' and '" + two.name +
          "' at one root of the same closure, so the angle constraints '" +
          c.angle_constraints[a].name + "' and '" + c.angle_constraints[b].name + "' at the ends of the joint '" +
          one.links[e].joint + "' they share are one equation";
  return t;
}

}  // namespace linkbox::verify
