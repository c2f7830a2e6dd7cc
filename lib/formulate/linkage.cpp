#include "formulate/linkage.hpp"

#include "model/vector_algebra.hpp"
#include "interval/rigorous.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

namespace linkbox::formulate {

using model::Polynomial;

namespace {

using Vec3 = model::Vec3<Interval>;
using model::cross;
using model::dot;

// theta = atan2(y, x) in (-pi, pi]; across the cut (x < 0, y around 0) as pi + atan2(-y, -x),
// an enclosure around pi instead of the whole circle.
Interval angle(const Interval& y, const Interval& x) {
  if (x.upper() < 0 && zero_in(y)) return rigorous::pi() + rigorous::atan2(-y, -x);
  return rigorous::atan2(y, x);
}

}  // namespace

LinkageFormulation::LinkageFormulation(input::LinkageCase c, LinkageOptions options)
    : case_(std::move(c)), options_(options) {
  input::validate(case_);
  index_case();
  ground_frame();
  build_model();
  plan_natural();
}

void LinkageFormulation::index_case() {
  index_joints();
  index_normals();
  list_outputs();
  const int joints = static_cast<int>(joint_names_.size());
  vectors_.assign(joints + normals_.size(), VectorModel{});
  constant_.assign(vectors_.size(), false);
  offsets_.assign(joints, Coordinate{});
}

void LinkageFormulation::index_joints() {
  for (auto& loop : case_.loops)
    for (auto& e : loop.links)
      if (joint_index_.emplace(e.joint, static_cast<int>(joint_names_.size())).second) {
        joint_names_.push_back(e.joint);
        prismatic_.push_back(e.prismatic);
        has_prismatic_ = has_prismatic_ || e.prismatic;
      }
}

// One normal per (joint, link, next joint): loops through the same link between the same
// joints share it.
void LinkageFormulation::index_normals() {
  std::map<std::tuple<int, std::string, int>, int> normal_index;
  std::set<std::string> named_links;
  for (auto& loop : case_.loops) {
    const size_t n = loop.links.size();
    std::vector<int> ids;
    for (size_t i = 0; i < n; ++i) {
      const input::LoopLink& e = loop.links[i];
      const int in = joint_index_.at(e.joint), out = joint_index_.at(loop.links[(i + 1) % n].joint);
      auto [it, fresh] = normal_index.emplace(std::make_tuple(in, e.link, out), static_cast<int>(normals_.size()));
      if (fresh) {
        Normal nm;
        nm.joint_in = in;
        nm.joint_out = out;
        nm.name = named_links.insert(e.link).second ? "a[" + e.link + "]" : "a[" + e.link + "@" + loop.name + "]";
        nm.a = e.a;
        nm.alpha = e.alpha;
        nm.line = e.line;
        normals_.push_back(nm);
      }
      ids.push_back(it->second);
    }
    loop_normals_.push_back(std::move(ids));
  }
}

// Outputs: each joint once (first loop), then revolute joints seen between other normals.
void LinkageFormulation::list_outputs() {
  const int joints = static_cast<int>(joint_names_.size());
  std::vector<Output> extra;
  std::vector<bool> listed(joints, false);
  for (size_t l = 0; l < case_.loops.size(); ++l) {
    const auto& loop = case_.loops[l];
    const size_t n = loop.links.size();
    for (size_t i = 0; i < n; ++i) {
      Output o{loop.links[i].joint, joint_index_.at(loop.links[i].joint), loop_normals_[l][(i + n - 1) % n],
               loop_normals_[l][i]};
      if (!listed[o.joint]) {
        listed[o.joint] = true;
        outputs_.push_back(o);
        continue;
      }
      if (prismatic_[o.joint]) continue;
      bool seen = false;
      for (auto* list : {&outputs_, &extra})
        for (auto& p : *list)
          seen = seen || (p.joint == o.joint && p.normal_in == o.normal_in && p.normal_out == o.normal_out);
      if (seen) continue;
      o.name += "@" + loop.name;
      extra.push_back(o);
    }
  }
  std::stable_sort(outputs_.begin(), outputs_.end(), [](const Output& a, const Output& b) { return a.joint < b.joint; });
  outputs_.insert(outputs_.end(), extra.begin(), extra.end());
}

// Frame of the ground link g (first loop through it) = world frame: x = a_g, z = d_{g+1},
// so d_g = Rx(-alpha_g) e_z = (0, sin alpha_g, cos alpha_g).
void LinkageFormulation::ground_frame() {
  for (size_t l = 0; l < case_.loops.size(); ++l) {
    const auto& loop = case_.loops[l];
    for (size_t g = 0; g < loop.links.size(); ++g) {
      if (loop.links[g].link != case_.ground) continue;
      Normal& nm = normals_[loop_normals_[l][g]];
      nm.ground = true;
      ground_loop_ = static_cast<int>(l);
      ground_entry_ = static_cast<int>(g);
      const Interval zero(0.0), one(1.0);
      auto set = [&](int vector, const Interval& x, const Interval& y, const Interval& z) {
        vectors_[vector] = {Coordinate{-1, one, x}, Coordinate{-1, one, y}, Coordinate{-1, one, z}};
        constant_[vector] = true;
      };
      set(static_cast<int>(joint_names_.size()) + loop_normals_[l][g], one, zero, zero);
      set(nm.joint_out, zero, zero, one);
      set(nm.joint_in, zero, rigorous::sin(nm.alpha), rigorous::cos(nm.alpha));
      return;
    }
  }
}

std::vector<std::string> LinkageFormulation::model_notes() const {
  if (case_.joint_limits.empty()) return {};
  std::string list;
  for (auto& l : limits_) list += (list.empty() ? "" : "; ") + l.name;
  return {std::to_string(limits_.size()) + " joint limit" + (limits_.size() == 1 ? "" : "s") +
          " as inequalities (pruning and verification)" + (list.empty() ? "" : ": " + list)};
}

const LinkageFormulation::VectorModel* LinkageFormulation::normal(size_t loop, size_t position) const {
  const int n = loop_normals_.at(loop).at(position);
  return normals_[n].modelled ? &vectors_[joint_names_.size() + n] : nullptr;
}

const LinkageFormulation::Coordinate& LinkageFormulation::offset(size_t joint) const {
  if (!prismatic_.at(joint)) throw std::out_of_range("joint '" + joint_names_[joint] + "' is revolute");
  return offsets_[joint];
}

std::vector<std::string> LinkageFormulation::output_names() const {
  std::vector<std::string> names;
  for (auto& o : outputs_) names.push_back(o.name);
  return names;
}

std::array<Interval, 3> LinkageFormulation::vector_value(int vector, const Box& box) const {
  const int joints = static_cast<int>(joint_names_.size());
  if (vector >= joints && !normals_[vector - joints].modelled) {
    // Left out of the model: a = (d_in x d_out) / sin(alpha). Only its direction matters
    // for the angles, so the positive factor 1 / |sin(alpha)| is dropped.
    const Normal& nm = normals_[vector - joints];
    Vec3 a = cross(vector_value(nm.joint_in, box), vector_value(nm.joint_out, box));
    if (nm.negative_sine)
      for (auto& x : a) x = -x;
    return a;
  }
  Vec3 r;
  for (int k = 0; k < 3; ++k) {
    r[k] = vectors_[vector][k].at(box);
  }
  return r;
}

bool LinkageFormulation::Coordinate::is_variable() const {
  return variable >= 0 && scale.lower() == 1 && scale.upper() == 1 && value.lower() == 0 && value.upper() == 0;
}

Interval LinkageFormulation::Coordinate::at(const Box& box) const {
  return variable < 0 ? value : value + scale * box.at(variable);
}

Box LinkageFormulation::to_output(size_t, const Box& box) const {
  const int joints = static_cast<int>(joint_names_.size());
  Box out;
  for (auto& o : outputs_) {
    if (o.is_offset(prismatic_)) {
      out.push_back(offsets_[o.joint].at(box));
      continue;
    }
    // theta = angle from a_in to a_out about d; both normals may carry positive scale factors.
    const Vec3 d = vector_value(o.joint, box), ain = vector_value(joints + o.normal_in, box),
               aout = vector_value(joints + o.normal_out, box);
    out.push_back(angle(dot(cross(ain, aout), d), dot(ain, aout)));
  }
  return out;
}

}  // namespace linkbox::formulate
