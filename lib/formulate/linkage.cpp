#include "formulate/linkage.hpp"

#include "formulate/linear_elimination.hpp"
#include "formulate/to_lph.hpp"
#include "model/vector_algebra.hpp"
#include "interval/rigorous.hpp"

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <map>
#include <numeric>
#include <ostream>
#include <set>
#include <sstream>
#include <tuple>

namespace linkbox::formulate {

using model::Polynomial;

std::string to_string(const ModelSize& s) {
  return std::to_string(s.primary) + " primary + " + std::to_string(s.dummy) + " dummy; " +
         std::to_string(s.linear) + " L, " + std::to_string(s.parabolic) + " P, " + std::to_string(s.hyperbolic) +
         " H";
}

std::ostream& operator<<(std::ostream& os, const ModelSize& s) { return os << to_string(s); }

namespace {

bool is_exact_zero(const Interval& x) { return x.lower() == 0 && x.upper() == 0; }

using VecP = model::Vec3<Polynomial>;
using Vec3 = model::Vec3<Interval>;
using model::cross;
using model::dot;

VecP constant_vector(const Interval& x, const Interval& y, const Interval& z) {
  return {Polynomial::constant(x), Polynomial::constant(y), Polynomial::constant(z)};
}

Polynomial renumber(const Polynomial& p, const std::vector<int>& index) {
  Polynomial r;
  for (auto& [original, c] : p.terms()) {
    model::Powers powers = original;
    for (auto& [v, e] : powers) v = index[v];
    std::sort(powers.begin(), powers.end());
    r += Polynomial::monomial(powers, c);
  }
  return r;
}

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
  for (auto& loop : case_.loops)
    for (auto& e : loop.links)
      if (joint_index_.emplace(e.joint, static_cast<int>(joint_names_.size())).second) {
        joint_names_.push_back(e.joint);
        prismatic_.push_back(e.prismatic);
        has_prismatic_ = has_prismatic_ || e.prismatic;
      }

  // One normal per (joint, link, next joint): loops through the same link between the same
  // joints share it.
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

  // Outputs: each joint once (first loop), then revolute joints seen between other normals.
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

  vectors_.assign(joints + normals_.size(), VectorModel{});
  constant_.assign(vectors_.size(), false);
  offsets_.assign(joints, Coordinate{});
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

void LinkageFormulation::build_model() {
  const int joints = static_cast<int>(joint_names_.size());

  // Which normals the model needs: those in a loop closure (a != 0), next to a prismatic
  // joint (its theta relation), or whose twist may be 0 or pi (then (3) does not fix them).
  for (auto& nm : normals_) {
    const Interval s = rigorous::sin(nm.alpha);
    nm.negative_sine = s.upper() < 0;
    nm.modelled = nm.ground || options_.keep_free_normals || !is_exact_zero(nm.a) || zero_in(s);
  }
  for (size_t l = 0; l < case_.loops.size(); ++l) {
    const size_t n = case_.loops[l].links.size();
    for (size_t i = 0; i < n; ++i)
      if (case_.loops[l].links[i].prismatic)
        normals_[loop_normals_[l][i]].modelled = normals_[loop_normals_[l][(i + n - 1) % n]].modelled = true;
  }

  // Provisional variables: coordinates of the non-ground vectors, then prismatic offsets.
  std::vector<model::Variable> vars;
  std::vector<VecP> vec(vectors_.size());
  static const char* axis_name[] = {".x", ".y", ".z"};
  for (size_t v = 0; v < vectors_.size(); ++v) {
    const bool is_axis = static_cast<int>(v) < joints;
    if (constant_[v]) {
      vec[v] = constant_vector(vectors_[v][0].value, vectors_[v][1].value, vectors_[v][2].value);
      continue;
    }
    if (!is_axis && !normals_[v - joints].modelled) continue;
    const std::string base = is_axis ? "d[" + joint_names_[v] + "]" : normals_[v - joints].name;
    for (int k = 0; k < 3; ++k) {
      vectors_[v][k].variable = static_cast<int>(vars.size());
      vec[v][k] = Polynomial::variable(static_cast<int>(vars.size()));
      vars.push_back({base + axis_name[k], Interval(-1.0, 1.0)});
    }
  }
  std::vector<Polynomial> offset(joints);
  for (auto& loop : case_.loops)
    for (auto& e : loop.links) {
      if (!e.prismatic) continue;
      const int j = joint_index_.at(e.joint);
      if (offsets_[j].variable >= 0) continue;
      offsets_[j].variable = static_cast<int>(vars.size());
      offset[j] = Polynomial::variable(static_cast<int>(vars.size()));
      vars.push_back({"offset[" + e.joint + "]", e.d});
    }

  std::vector<NamedEquation> eqs;
  auto add3 = [&](const VecP& v, const std::string& name, int line) {
    for (int k = 0; k < 3; ++k) eqs.push_back({v[k], name + " (" + std::string(axis_name[k] + 1) + ")", line});
  };
  auto minus = [](const VecP& u, const VecP& v) { return VecP{u[0] - v[0], u[1] - v[1], u[2] - v[2]}; };
  auto times = [](const VecP& u, const Interval& c) { return VecP{u[0] * c, u[1] * c, u[2] * c}; };
  const Polynomial one = Polynomial::constant(Interval(1.0));

  // (1) unit vectors.
  std::vector<int> first_line(joints, 0);
  for (auto& loop : case_.loops)
    for (auto& e : loop.links) {
      const int j = joint_index_.at(e.joint);
      if (!first_line[j]) first_line[j] = e.line;
    }
  for (int j = 0; j < joints; ++j) eqs.push_back({dot(vec[j], vec[j]) - one, "|d[" + joint_names_[j] + "]| = 1", first_line[j]});
  for (size_t n = 0; n < normals_.size(); ++n)
    if (normals_[n].modelled) eqs.push_back({dot(vec[joints + n], vec[joints + n]) - one, "|" + normals_[n].name + "| = 1", normals_[n].line});

  // (3), (4) per link between its two joints.
  for (size_t n = 0; n < normals_.size(); ++n) {
    const Normal& nm = normals_[n];
    const VecP &din = vec[nm.joint_in], &dout = vec[nm.joint_out], &a = vec[joints + n];
    const Interval s = rigorous::sin(nm.alpha), co = rigorous::cos(nm.alpha);
    eqs.push_back({dot(din, dout) - Polynomial::constant(co), nm.name + ": d . d' = cos(alpha)", nm.line});
    if (!nm.modelled) continue;
    add3(minus(cross(din, dout), times(a, s)), nm.name + ": d x d' = sin(alpha) a", nm.line);
    if (zero_in(s)) {  // twist 0 or pi (or too close to tell): (3) leaves a free, pin it
      eqs.push_back({dot(a, din), nm.name + ": a . d = 0", nm.line});
      eqs.push_back({dot(a, dout), nm.name + ": a . d' = 0", nm.line});
    }
  }

  // (2) loop closure; prismatic joints' theta relations.
  std::set<std::tuple<int, int, int>> prismatic_done;
  for (size_t l = 0; l < case_.loops.size(); ++l) {
    const auto& loop = case_.loops[l];
    const size_t n = loop.links.size();
    VecP sum;
    for (size_t i = 0; i < n; ++i) {
      const input::LoopLink& e = loop.links[i];
      const int j = normals_[loop_normals_[l][i]].joint_in;
      const Polynomial length = e.prismatic ? offset[j] : Polynomial::constant(e.d);
      for (int k = 0; k < 3; ++k) {
        sum[k] += length * vec[j][k];
        if (!is_exact_zero(e.a)) sum[k] += vec[joints + loop_normals_[l][i]][k] * e.a;
      }
      if (!e.prismatic) continue;
      const int prev = loop_normals_[l][(i + n - 1) % n], next = loop_normals_[l][i];
      if (!prismatic_done.insert({prev, j, next}).second) continue;
      const VecP &ap = vec[joints + prev], &an = vec[joints + next];
      const std::string name = "joint " + e.joint;
      eqs.push_back({dot(ap, an) - Polynomial::constant(rigorous::cos(e.theta)), name + ": a . a' = cos(theta)", e.line});
      add3(minus(cross(ap, an), times(vec[j], rigorous::sin(e.theta))), name + ": a x a' = sin(theta) d", e.line);
    }
    add3(sum, "loop " + loop.name + ": closure", loop.line);
  }

  // Angle constraints between axes.
  for (auto& ac : case_.angle_constraints) {
    eqs.push_back({dot(vec[joint_index_.at(ac.joint1)], vec[joint_index_.at(ac.joint2)]) - Polynomial::constant(rigorous::cos(ac.angle)),
                   "angle " + (ac.name.empty() ? ac.joint1 + "," + ac.joint2 : ac.name) + ": d . d' = cos(angle)",
                   ac.line});
  }

  const std::vector<Affine> elimination = eliminate_linear(eqs, vars, case_.file);

  // Drop equations left constant (0 = 0 up to rounding); a non-zero constant is a
  // contradiction already between ground and parameters.
  std::vector<NamedEquation> kept;
  for (auto& eq : eqs) {
    if (!eq.p.is_constant()) {
      kept.push_back(std::move(eq));
      continue;
    }
    const Interval k = eq.p.constant_term();
    if (!zero_in(k)) {
      std::ostringstream value;
      value << std::setprecision(3) << median(k);
      throw input::InputError(case_.file, eq.line,
                         "the linkage cannot be assembled: '" + eq.name + "' reduces to " + value.str() +
                             " = 0 (an overconstrained linkage closes only if its parameters satisfy its closure "
                             "condition exactly: write them as exact expressions such as \"pi/3\")");
    }
  }

  // Keep only variables that occur; renumber.
  std::vector<int> index(vars.size(), -1);
  model::System primary;
  for (auto& eq : kept)
    for (int v : eq.p.variables()) index[v] = 0;
  for (size_t v = 0; v < vars.size(); ++v)
    if (index[v] == 0) {
      index[v] = static_cast<int>(primary.variables.size());
      primary.variables.push_back(vars[v]);
    }
  std::vector<std::string> names;
  for (auto& eq : kept) {
    primary.equations.push_back(renumber(eq.p, index));
    names.push_back(eq.name);
  }
  primary.equation_names = names;

  // Coordinates: through the eliminations to a surviving variable or a constant; a variable
  // that occurs in no equation is unconstrained and stands for its domain.
  auto place = [&](Coordinate& c) {
    if (c.variable < 0) return;
    const Affine& r = elimination[c.variable];
    if (r.variable >= 0 && index[r.variable] >= 0) {
      c = {index[r.variable], r.scale, r.offset};
    } else {
      const Interval free = r.variable >= 0 ? r.scale * vars[r.variable].domain : Interval(0.0);
      c = {-1, Interval(1.0), r.offset + free};
    }
  };
  for (size_t v = 0; v < vectors_.size(); ++v)
    for (auto& c : vectors_[v]) place(c);
  for (auto& c : offsets_) place(c);

  // Joint limits: cos(h) |a_in| |a_out| - (a_in . a_out) cos(m) - ((a_in x a_out) . d) sin(m)
  // <= 0, where |a| is 1 for a modelled normal and |sin(alpha)| for one left out (its
  // vector is d_in x d_out there).
  for (const input::JointLimit& jl : case_.joint_limits) {
    const Interval lo(jl.lower.lower()), hi(jl.upper.upper()), pi = rigorous::pi();
    char bounds[64];
    std::snprintf(bounds, sizeof bounds, "[%.6g, %.6g]", median(jl.lower), median(jl.upper));
    Limit l{-1, (lo + hi) / Interval(2.0), (hi - lo) / Interval(2.0), jl.joint + " in " + bounds};
    if (l.half.upper() >= pi.lower()) continue;  // a full turn: no limit
    for (size_t k = 0; k < outputs_.size() && l.output < 0; ++k)
      if (!outputs_[k].turn && outputs_[k].name == jl.joint) l.output = static_cast<int>(k);
    if (l.output < 0) throw std::logic_error("linkage: no output for limited joint " + jl.joint);
    const Output& o = outputs_[l.output];
    const VecP d = vector_polynomial(o.joint), ain = vector_polynomial(joints + o.normal_in),
               aout = vector_polynomial(joints + o.normal_out);
    Interval scale(1.0);
    for (int n : {o.normal_in, o.normal_out})
      if (!normals_[n].modelled) scale *= boost::numeric::abs(rigorous::sin(normals_[n].alpha));
    model::Inequality g;
    g.g = Polynomial::constant(scale * rigorous::cos(l.half)) - dot(ain, aout) * rigorous::cos(l.mid) -
          dot(cross(ain, aout), d) * rigorous::sin(l.mid);
    g.name = "joint limit " + l.name;
    primary.inequalities.push_back(std::move(g));
    limits_.push_back(std::move(l));
  }

  auto lph = std::make_shared<model::LphSystem>(to_lph(primary));
  sub_.label = "all";
  sub_.system = lph_polynomials(*lph, names);
  for (size_t v = 0; v < primary.variables.size(); ++v) sub_.split_dims.push_back(static_cast<int>(v));
  sub_.lph = std::move(lph);
  sub_.unlifted = std::make_shared<const model::System>(std::move(primary));
}

std::array<Polynomial, 3> LinkageFormulation::vector_polynomial(int vector) const {
  const int joints = static_cast<int>(joint_names_.size());
  if (vector >= joints && !normals_[vector - joints].modelled) {
    const Normal& nm = normals_[vector - joints];
    VecP a = cross(vector_polynomial(nm.joint_in), vector_polynomial(nm.joint_out));
    if (nm.negative_sine)
      for (auto& x : a) x = -x;
    return a;
  }
  VecP r;
  for (int k = 0; k < 3; ++k) {
    const Coordinate& c = vectors_[vector][k];
    r[k] = Polynomial::constant(c.value);
    if (c.variable >= 0) r[k] += Polynomial::variable(c.variable) * c.scale;
  }
  return r;
}

std::vector<std::string> LinkageFormulation::model_notes() const {
  if (case_.joint_limits.empty()) return {};
  std::string list;
  for (auto& l : limits_) list += (list.empty() ? "" : "; ") + l.name;
  return {std::to_string(limits_.size()) + " joint limit" + (limits_.size() == 1 ? "" : "s") +
          " as inequalities (pruning and verification)" + (list.empty() ? "" : ": " + list)};
}

ModelSize LinkageFormulation::model_size() const {
  const model::LphSystem& s = *sub_.lph;
  const int primary = static_cast<int>(s.primary.size());
  return {primary, static_cast<int>(s.variables.size()) - primary, static_cast<int>(s.linear.size()),
          static_cast<int>(s.parabolic.size()), static_cast<int>(s.hyperbolic.size())};
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
