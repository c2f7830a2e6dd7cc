// LinkageFormulation's certification charts: the loop closures in joint variables, with the
// loops placed from the ground link's frame so that angle constraints between their axes
// are polynomial too.
//
// Why a turn and nothing else places a further loop: the loop shares joint J (from link A
// to link B) with a placed loop. Both loops' frames at A have z = d_J, so they differ by a
// rotation about d_J (the turn phi); the frames at B do too, by some psi, and the angle at J
// seen in the new loop is the placed one plus psi - phi. psi occurs nowhere else, so the
// new loop's angle at J is an unknown of its own ("J@loop") and psi is not needed. Each
// loop's closure holds in any frame, and no output depends on where a loop sits along J,
// so only angle constraints between loops need the turn.
#include "formulate/half_angle.hpp"
#include "formulate/linkage.hpp"
#include "formulate/loop_closure.hpp"
#include "interval/rigorous.hpp"

#include <map>
#include <set>
#include <stdexcept>

namespace linkbox::formulate {

using model::Polynomial;

namespace {

std::string quote(const std::string& s) { return "'" + s + "'"; }

// Entry before `entry` round a loop of n entries (its link runs into the entry's joint).
int before(int entry, size_t n) { return static_cast<int>((entry + n - 1) % n); }

// What is left of two chains from the world frame after their common start: the rotation
// between the frames they reach is conj(prod first) * prod second.
template <class Chain>
std::pair<Chain, Chain> after_common_start(const Chain& a, const Chain& b) {
  size_t k = 0;
  while (k < a.size() && k < b.size() && a[k] == b[k]) ++k;
  return {Chain(a.begin() + k, a.end()), Chain(b.begin() + k, b.end())};
}

}  // namespace

void LinkageFormulation::plan_natural() {
  const size_t loops = case_.loops.size();
  std::vector<std::map<int, int>> entry_of(loops);  // [loop]: joint -> its entry there
  for (size_t l = 0; l < loops; ++l)
    for (size_t i = 0; i < case_.loops[l].links.size(); ++i)
      entry_of[l][joint_index_.at(case_.loops[l].links[i].joint)] = static_cast<int>(i);

  placements_.push_back({ground_loop_, -1, -1, -1, -1});
  std::vector<bool> placed(loops, false);
  placed[ground_loop_] = true;
  while (placements_.size() < loops) {
    // The first loop in case order that shares a joint with those placed.
    int next = -1;
    std::vector<int> shared;
    for (size_t l = 0; l < loops && next < 0; ++l) {
      if (placed[l]) continue;
      shared.clear();
      for (auto [joint, entry] : entry_of[l])
        for (auto& p : placements_)
          if (entry_of[p.loop].count(joint)) {
            shared.push_back(joint);
            break;
          }
      if (!shared.empty()) next = static_cast<int>(l);
    }
    if (next < 0) {
      size_t l = 0;
      while (placed[l]) ++l;
      no_natural_ = "loop " + quote(case_.loops[l].name) +
                    " shares no joint with the loops placed before it (only angle constraints tie it to them), "
                    "so its orientation is a general rotation: not supported";
      return;
    }
    if (shared.size() > 1) {
      std::string names;
      for (int j : shared) names += (names.empty() ? "" : ", ") + quote(joint_names_[j]);
      no_natural_ = "loop " + quote(case_.loops[next].name) + " shares " + std::to_string(shared.size()) +
                    " joints (" + names + ") with the loops placed before it; only one shared joint per loop is " +
                    "supported";
      return;
    }
    const int joint = shared[0];
    Placement p{next, -1, entry_of[next].at(joint), -1, -1};
    for (auto& q : placements_)
      if (entry_of[q.loop].count(joint)) {
        p.parent = q.loop;
        p.parent_entry = entry_of[q.loop].at(joint);
        break;
      }
    placements_.push_back(p);
    placed[next] = true;
  }

  // The unknown of each entry: the output that measures its joint between its normals.
  unknown_of_entry_.assign(loops, {});
  for (size_t l = 0; l < loops; ++l) {
    const size_t n = case_.loops[l].links.size();
    for (size_t i = 0; i < n; ++i) {
      const int joint = joint_index_.at(case_.loops[l].links[i].joint);
      const int in = loop_normals_[l][before(static_cast<int>(i), n)], out = loop_normals_[l][i];
      int found = -1;
      for (size_t k = 0; k < outputs_.size() && found < 0; ++k) {
        const Output& o = outputs_[k];
        if (o.joint == joint && (prismatic_[joint] || (o.normal_in == in && o.normal_out == out)))
          found = static_cast<int>(k);
      }
      if (found < 0) throw std::logic_error("linkage: no output for joint " + joint_names_[joint]);
      unknown_of_entry_[l].push_back(found);
    }
  }

  // Turns that an angle constraint sees become outputs (and natural unknowns).
  std::set<int> turned;
  for (auto& ac : case_.angle_constraints) {
    auto [first, second] = after_common_start(axis_chain(joint_index_.at(ac.joint1)), axis_chain(joint_index_.at(ac.joint2)));
    for (auto* chain : {&first, &second})
      for (auto& f : *chain)
        if (f.kind == ChainFactor::turn) turned.insert(f.loop);
  }
  for (auto& p : placements_) {
    if (!turned.count(p.loop)) continue;
    const auto& loop = case_.loops[p.loop];
    const int a = before(p.entry, loop.links.size());
    Output o;
    o.name = "turn[" + loop.links[a].link + "@" + loop.name + "]";
    o.joint = joint_index_.at(loop.links[p.entry].joint);
    o.normal_in = loop_normals_[p.parent][before(p.parent_entry, case_.loops[p.parent].links.size())];
    o.normal_out = loop_normals_[p.loop][a];
    o.turn = true;
    p.turn = static_cast<int>(outputs_.size());
    outputs_.push_back(o);
  }
  if (outputs_.size() > 64) no_natural_ = "more than 64 outputs (charts are 64-bit masks of half-turn shifts)";
}

std::vector<LinkageFormulation::ChainFactor> LinkageFormulation::frame_chain(int loop, int position) const {
  const Placement* p = nullptr;
  for (auto& q : placements_)
    if (q.loop == loop) p = &q;
  const int n = static_cast<int>(case_.loops[loop].links.size());
  std::vector<ChainFactor> chain;
  int from = ground_entry_;
  if (p->parent >= 0) {
    chain = frame_chain(p->parent, before(p->parent_entry, case_.loops[p->parent].links.size()));
    chain.push_back({ChainFactor::turn, loop, -1, false});
    from = before(p->entry, n);
  }
  // Frame i = frame (i-1) Rz(theta_i) Rx(alpha_i): the shorter way round the loop.
  const int forward = (position - from + n) % n;
  if (forward <= n - forward) {
    for (int k = 1; k <= forward; ++k) {
      const int i = (from + k) % n;
      chain.push_back({ChainFactor::joint, loop, i, false});
      chain.push_back({ChainFactor::twist, loop, i, false});
    }
  } else {
    for (int k = 0; k < n - forward; ++k) {
      const int i = (from - k + n) % n;
      chain.push_back({ChainFactor::twist, loop, i, true});
      chain.push_back({ChainFactor::joint, loop, i, true});
    }
  }
  return chain;
}

std::vector<LinkageFormulation::ChainFactor> LinkageFormulation::axis_chain(int joint) const {
  for (auto& p : placements_) {
    const auto& links = case_.loops[p.loop].links;
    for (size_t i = 0; i < links.size(); ++i) {
      if (joint_index_.at(links[i].joint) != joint) continue;
      // The axis is z of the frame of the link before the joint; rotations about z at the
      // end of the chain leave it as it is.
      auto chain = frame_chain(p.loop, before(static_cast<int>(i), links.size()));
      while (!chain.empty() && chain.back().kind != ChainFactor::twist) chain.pop_back();
      return chain;
    }
  }
  throw std::logic_error("linkage: joint " + joint_names_.at(joint) + " in no placed loop");
}

Polynomial LinkageFormulation::angle_equation(const input::AngleConstraint& ac, std::uint64_t chart) const {
  auto factor = [&](const ChainFactor& f) {
    const input::LoopLink& e = case_.loops[f.loop].links[f.entry < 0 ? 0 : f.entry];
    RotationFactor r;
    if (f.kind == ChainFactor::twist) {
      r = rotation_about_x(e.alpha);
    } else if (f.kind == ChainFactor::joint) {
      r = e.prismatic ? fixed_rotation_about_z(e.theta) : rotation_about_z(unknown_of_entry_[f.loop][f.entry], chart);
    } else {
      int turn = -1;
      for (auto& p : placements_)
        if (p.loop == f.loop) turn = p.turn;
      if (turn < 0) throw std::logic_error("linkage: an angle constraint sees a turn that is no unknown");
      r = rotation_about_z(turn, chart);
    }
    if (f.inverse) r.q = conjugate(r.q);
    return r;
  };
  auto product = [&](const std::vector<ChainFactor>& chain) {
    RotationFactor r{{Polynomial::constant(Interval(1.0)), Polynomial(), Polynomial(), Polynomial()},
                     Polynomial::constant(Interval(1.0))};
    for (auto& f : chain) {
      const RotationFactor g = factor(f);
      r = {qmul(r.q, g.q), r.norm2 * g.norm2};
    }
    return r;
  };
  auto [first, second] = after_common_start(axis_chain(joint_index_.at(ac.joint1)), axis_chain(joint_index_.at(ac.joint2)));
  const RotationFactor a = product(first), b = product(second);
  // d1 . d2 = z . (R z) for R = conj(A) B, the rotation from frame 1 to frame 2; its
  // unnormalised (3, 3) entry is w^2 + z^2 - x^2 - y^2, and |R|^2 = |A|^2 |B|^2 > 0.
  const QuaternionPolynomial r = qmul(conjugate(a.q), b.q);
  return r[0] * r[0] + r[3] * r[3] - r[1] * r[1] - r[2] * r[2] - a.norm2 * b.norm2 * rigorous::cos(ac.angle);
}

std::uint64_t LinkageFormulation::angle_outputs() const {
  std::uint64_t m = 0;
  for (size_t k = 0; k < outputs_.size() && k < 64; ++k)
    if (!outputs_[k].is_offset(prismatic_)) m |= std::uint64_t{1} << k;
  return m;
}

std::uint64_t LinkageFormulation::chart_for(const Box& output_hull) const {
  return no_natural_.empty() ? half_turn_chart(output_hull, angle_outputs()) : 0;
}

NaturalSystem LinkageFormulation::natural_system(std::uint64_t chart) const {
  NaturalSystem s;
  if (!no_natural_.empty()) {
    s.missing = no_natural_;
    return s;
  }
  for (auto& o : outputs_) s.unknowns.push_back(o.is_offset(prismatic_) ? o.name : "t_" + o.name);
  for (size_t l = 0; l < case_.loops.size(); ++l) {
    const int first = static_cast<int>(s.equations.size());
    for (auto& p : dh_loop_closure(case_.loops[l], unknown_of_entry_[l], chart)) s.equations.push_back(std::move(p));
    s.loop_rows.emplace_back(first, static_cast<int>(s.equations.size()));
  }
  for (auto& ac : case_.angle_constraints) s.equations.push_back(angle_equation(ac, chart));
  for (auto& l : limits_) s.inequalities.push_back(limit_inequality(l, chart));
  if (has_prismatic_) {
    // Offsets count within their ranges; tangents are unbounded (charts cover the circle).
    std::map<int, Interval> range;
    for (auto& loop : case_.loops)
      for (auto& e : loop.links)
        if (e.prismatic) range.emplace(joint_index_.at(e.joint), e.d);
    for (auto& o : outputs_) s.domain.push_back(o.is_offset(prismatic_) ? range.at(o.joint) : Interval(-1e300, 1e300));
  }
  return s;
}

// theta = 2 atan(t) + s pi: cos theta = sigma (1 - t^2) / (1 + t^2), sin theta = sigma 2t /
// (1 + t^2), sigma = (-1)^s; multiplied by 1 + t^2 > 0.
model::Inequality LinkageFormulation::limit_inequality(const Limit& l, std::uint64_t chart) const {
  const Polynomial t = Polynomial::variable(l.output), one = Polynomial::constant(Interval(1.0)), t2 = t * t;
  const bool shifted = l.output < 64 && (chart >> l.output & 1);
  Polynomial arc = (one - t2) * rigorous::cos(l.mid) + t * (Interval(2.0) * rigorous::sin(l.mid));
  if (shifted) arc = -arc;
  return {(one + t2) * rigorous::cos(l.half) - arc, false, "joint limit " + l.name};
}

Box LinkageFormulation::output_to_natural(std::uint64_t chart, const Box& output) const {
  return no_natural_.empty() ? angles_to_tangents(chart, output, angle_outputs()) : output;
}

Box LinkageFormulation::natural_to_output(std::uint64_t chart, const Box& natural) const {
  return no_natural_.empty() ? tangents_to_angles(chart, natural, angle_outputs()) : natural;
}

}  // namespace linkbox::formulate
