#include "formulate/linkage.hpp"

#include "formulate/to_lph.hpp"
#include "interval/rigorous.hpp"

#include <algorithm>
#include <iomanip>
#include <map>
#include <numeric>
#include <ostream>
#include <set>
#include <sstream>
#include <tuple>

namespace linkbox::formulate {

using model::Polynomial;

LinkageError::LinkageError(const std::string& file, int line, const std::string& message)
    : std::invalid_argument(file + ":" + std::to_string(line) + ": " + message), line(line), message(message) {}

std::string to_string(const ModelSize& s) {
  return std::to_string(s.primary) + " primary + " + std::to_string(s.dummy) + " dummy; " +
         std::to_string(s.linear) + " L, " + std::to_string(s.parabolic) + " P, " + std::to_string(s.hyperbolic) +
         " H";
}

std::ostream& operator<<(std::ostream& os, const ModelSize& s) { return os << to_string(s); }

namespace {

bool same(const Interval& x, const Interval& y) { return x.lower() == y.lower() && x.upper() == y.upper(); }
bool is_exact_zero(const Interval& x) { return x.lower() == 0 && x.upper() == 0; }
std::string quote(const std::string& s) { return "'" + s + "'"; }
std::string at_line(int line) { return " (line " + std::to_string(line) + ")"; }

// Smallest-index representative, with path halving.
int find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

// What a case must satisfy before it is modelled:
//  - at least one loop, unique loop names, at least 3 links per loop, non-empty names;
//  - a loop passes each joint and each link at most once;
//  - a joint joins the same two links, in the same direction, in every loop through it (its
//    axis d is one vector), and has the same type (and for a prismatic joint the same theta
//    and range) everywhere;
//  - a link seen between the same two joints in several loops has the same a and alpha there,
//    and a link in several loops keeps one of its joints in all of them (otherwise nothing in
//    the vector model would tie the two appearances together);
//  - parameters finite, prismatic ranges non-empty;
//  - the ground link exists; angle constraints name two different known joints;
//  - every loop is tied to the ground's loops through shared joints or angle constraints
//    (a loop tied to nothing could turn freely as a whole).
void validate(const LinkageCase& c) {
  auto fail = [&](int line, const std::string& m) { throw LinkageError(c.file, line, m); };
  if (c.loops.empty()) fail(0, "no loops");

  struct JointUse {
    const LinkageLoop* loop;
    const LoopLink* entry;
    std::string prev, next;
  };
  struct LinkUse {
    const LinkageLoop* loop;
    const LoopLink* entry;
    std::string in, out;
  };
  std::map<std::string, int> loop_lines;
  std::map<std::string, JointUse> joints;
  std::map<std::string, LinkUse> links;
  std::map<std::tuple<std::string, std::string, std::string>, const LoopLink*> normals;
  std::map<std::string, std::vector<int>> loops_of_joint;
  std::map<std::string, int> loop_of_link;  // first loop through each link

  for (size_t l = 0; l < c.loops.size(); ++l) {
    const LinkageLoop& loop = c.loops[l];
    if (loop.name.empty()) fail(loop.line, "empty loop name");
    if (auto [it, fresh] = loop_lines.emplace(loop.name, loop.line); !fresh)
      fail(loop.line, "duplicate loop name " + quote(loop.name) + " (first declared on line " +
                          std::to_string(it->second) + ")");
    const size_t n = loop.links.size();
    if (n < 3)
      fail(loop.line, "loop " + quote(loop.name) + " has " + std::to_string(n) +
                          " link(s); a loop needs at least 3 (joints and links alternate around it)");
    std::map<std::string, int> joints_here, links_here;
    for (const LoopLink& e : loop.links) {
      if (e.link.empty()) fail(e.line, "empty link name");
      if (e.joint.empty()) fail(e.line, "empty joint name");
      if (auto [it, fresh] = joints_here.emplace(e.joint, e.line); !fresh)
        fail(e.line, "joint " + quote(e.joint) + " appears twice in loop " + quote(loop.name) + " (also on line " +
                         std::to_string(it->second) + "): a loop passes each joint once");
      if (auto [it, fresh] = links_here.emplace(e.link, e.line); !fresh)
        fail(e.line, "link " + quote(e.link) + " appears twice in loop " + quote(loop.name) + " (also on line " +
                         std::to_string(it->second) + "): a loop passes each link once");
      for (const Interval* v : {&e.a, &e.alpha, &e.d})
        if (!is_finite(*v)) fail(e.line, "parameter of link " + quote(e.link) + " is not finite");
      if (e.prismatic && !is_finite(e.theta)) fail(e.line, "theta of joint " + quote(e.joint) + " is not finite");
      if (e.prismatic && !(e.d.lower() <= e.d.upper()))
        fail(e.line, "empty range of the offset d of prismatic joint " + quote(e.joint));
    }
    for (size_t i = 0; i < n; ++i) {
      const LoopLink& e = loop.links[i];
      const std::string& prev = loop.links[(i + n - 1) % n].link;
      const std::string& next_joint = loop.links[(i + 1) % n].joint;
      loops_of_joint[e.joint].push_back(static_cast<int>(l));
      loop_of_link.emplace(e.link, static_cast<int>(l));

      if (auto [it, fresh] = joints.emplace(e.joint, JointUse{&loop, &e, prev, e.link}); !fresh) {
        const JointUse& u = it->second;
        const std::string there = " in loop " + quote(u.loop->name) + at_line(u.entry->line);
        if (u.entry->prismatic != e.prismatic)
          fail(e.line, "joint " + quote(e.joint) + " is " + (e.prismatic ? "prismatic" : "revolute") + " here but " +
                           (u.entry->prismatic ? "prismatic" : "revolute") + there);
        if (u.prev != prev || u.next != e.link)
          fail(e.line, "joint " + quote(e.joint) + " joins links " + quote(prev) + " -> " + quote(e.link) +
                           " here but " + quote(u.prev) + " -> " + quote(u.next) + there +
                           ": a joint joins the same two links in every loop, passed in the same direction");
        if (e.prismatic && (!same(e.theta, u.entry->theta) || !same(e.d, u.entry->d)))
          fail(e.line, "prismatic joint " + quote(e.joint) + " has another theta or range than" + there);
      }
      if (auto [it, fresh] = links.emplace(e.link, LinkUse{&loop, &e, e.joint, next_joint}); !fresh) {
        const LinkUse& u = it->second;
        if (u.in != e.joint && u.out != next_joint)
          fail(e.line, "link " + quote(e.link) + " runs from joint " + quote(e.joint) + " to " + quote(next_joint) +
                           " here but from " + quote(u.in) + " to " + quote(u.out) + " in loop " +
                           quote(u.loop->name) + at_line(u.entry->line) +
                           ": a link shared by loops must keep one of its joints in all of them");
      }
      if (auto [it, fresh] = normals.emplace(std::make_tuple(e.joint, e.link, next_joint), &e); !fresh) {
        const LoopLink& u = *it->second;
        if (!same(u.a, e.a) || !same(u.alpha, e.alpha))
          fail(e.line, "link " + quote(e.link) + " between joints " + quote(e.joint) + " and " + quote(next_joint) +
                           " has other a or alpha than on line " + std::to_string(u.line));
      }
    }
  }

  if (c.ground.empty()) fail(c.ground_line, "no ground link");
  auto ground = loop_of_link.find(c.ground);
  if (ground == loop_of_link.end()) fail(c.ground_line, "unknown ground link " + quote(c.ground) + " (in no loop)");

  std::vector<int> parent(c.loops.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto unite = [&](int a, int b) { parent[find(parent, a)] = find(parent, b); };
  for (auto& [joint, loops] : loops_of_joint)
    for (int l : loops) unite(l, loops.front());

  std::map<std::string, int> constraint_lines;
  for (const AngleConstraint& a : c.angle_constraints) {
    if (!a.name.empty())
      if (auto [it, fresh] = constraint_lines.emplace(a.name, a.line); !fresh)
        fail(a.line, "duplicate angle constraint name " + quote(a.name) + " (first declared on line " +
                         std::to_string(it->second) + ")");
    for (const std::string* j : {&a.joint1, &a.joint2})
      if (!joints.count(*j)) fail(a.line, "angle constraint names unknown joint " + quote(*j));
    if (a.joint1 == a.joint2) fail(a.line, "angle constraint between joint " + quote(a.joint1) + " and itself");
    if (!is_finite(a.angle)) fail(a.line, "angle constraint angle is not finite");
    unite(loops_of_joint[a.joint1].front(), loops_of_joint[a.joint2].front());
  }
  for (size_t l = 0; l < c.loops.size(); ++l)
    if (find(parent, static_cast<int>(l)) != find(parent, ground->second))
      fail(c.loops[l].line, "loop " + quote(c.loops[l].name) + " is not tied to the ground link " + quote(c.ground) +
                                ": it shares no joint (nor an angle constraint) with the loops through it, so it "
                                "could turn freely as a whole");
}

namespace {

using VecP = std::array<Polynomial, 3>;

Polynomial dot(const VecP& u, const VecP& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }
VecP cross(const VecP& u, const VecP& v) {
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}
VecP constant_vector(const Interval& x, const Interval& y, const Interval& z) {
  return {Polynomial::constant(x), Polynomial::constant(y), Polynomial::constant(z)};
}

using Vec3 = std::array<Interval, 3>;
Interval dot(const Vec3& u, const Vec3& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }
Vec3 cross(const Vec3& u, const Vec3& v) {
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

Polynomial renumber(const Polynomial& p, const std::vector<int>& index) {
  Polynomial r;
  for (auto& [powers, c] : p.terms()) {
    Polynomial mono = Polynomial::constant(c);
    for (auto [v, e] : powers) mono = mono * Polynomial::variable(index[v]).pow(e);
    r += mono;
  }
  return r;
}

// theta = atan2(y, x) in (-pi, pi]; across the cut (x < 0, y around 0) as pi + atan2(-y, -x),
// an enclosure around pi instead of the whole circle.
Interval angle(const Interval& y, const Interval& x) {
  if (x.upper() < 0 && zero_in(y)) return rigorous::pi() + rigorous::atan2(-y, -x);
  return rigorous::atan2(y, x);
}

struct Eq {
  Polynomial p;
  std::string name;
  int line;
};

// x = offset + scale * v[variable], or x = offset when variable < 0.
struct Affine {
  int variable = -1;
  Interval scale{1.0}, offset{0.0};
};

// p with variable `var` replaced by the polynomial r.
Polynomial substitute(const Polynomial& p, int var, const Polynomial& r) {
  Polynomial out;
  for (auto& [powers, c] : p.terms()) {
    Polynomial term = Polynomial::constant(c);
    for (auto [v, e] : powers) term = term * (v == var ? r.pow(e) : Polynomial::variable(v).pow(e));
    out += term;
  }
  return out;
}

size_t nonlinear_monomials(const std::vector<Eq>& eqs) {
  std::set<model::Powers> m;
  for (auto& eq : eqs)
    for (auto& [powers, c] : eq.p.terms()) {
      int degree = 0;
      for (auto [v, e] : powers) degree += e;
      if (degree >= 2) m.insert(powers);
    }
  return m.size();
}

// Eliminates variables through linear equations, until none applies:
//  - c x + k = 0 fixes x (always: the ground makes e.g. d_{g+2}.z = cos(alpha_{g+1}) one);
//  - c x + c' y + k = 0 gives x = -(k + c' y) / c, substituted when that does not add
//    products or squares (so the L/P/H model loses a variable and gains no dummy); x is the
//    one with the larger coefficient, so nothing is multiplied up, and y keeps to the values
//    that put x in its domain.
// The defining equation is consumed. With interval coefficients the substituted system
// contains every system with coefficients in the intervals: nothing is lost. Returns, per
// variable, what it became (itself when kept).
std::vector<Affine> eliminate_linear(std::vector<Eq>& eqs, std::vector<model::Variable>& vars, const std::string& file) {
  std::vector<Affine> as(vars.size());
  for (size_t v = 0; v < vars.size(); ++v) as[v].variable = static_cast<int>(v);
  auto eliminate = [&](size_t k, int x, const Interval& offset, int y, const Interval& scale) {
    const Polynomial r = y < 0 ? Polynomial::constant(offset)
                               : Polynomial::constant(offset) + Polynomial::variable(y) * scale;
    eqs.erase(eqs.begin() + k);
    for (auto& eq : eqs) eq.p = substitute(eq.p, x, r);
    for (auto& a : as)
      if (a.variable == x) a = y < 0 ? Affine{-1, Interval(1.0), a.offset + a.scale * offset}
                                     : Affine{y, a.scale * scale, a.offset + a.scale * offset};
  };
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t k = 0; k < eqs.size() && !changed; ++k) {
      const Eq& eq = eqs[k];
      if (eq.p.total_degree() != 1) continue;
      const std::vector<int> v = eq.p.variables();
      if (v.size() > 2) continue;
      auto coef = [&](int var) { return eq.p.terms().at(model::Powers{{var, 1}}); };
      const Interval k0 = eq.p.constant_term();
      if (v.size() == 1) {
        const Interval c = coef(v[0]);
        if (zero_in(c)) continue;
        Interval x = -k0 / c;
        if (!intersect(x, vars[v[0]].domain, x))
          throw LinkageError(file, eq.line,
                             "the linkage cannot be assembled: '" + eq.name + "' puts " + vars[v[0]].name +
                                 " outside its range");
        eliminate(k, v[0], x, -1, Interval(0.0));
        changed = true;
        continue;
      }
      const bool first = norm(coef(v[0])) >= norm(coef(v[1]));
      const int x = first ? v[0] : v[1], y = first ? v[1] : v[0];
      const Interval cx = coef(x), cy = coef(y);
      if (zero_in(cx)) continue;
      const Interval offset = -k0 / cx, scale = -cy / cx;
      std::vector<Eq> trial = eqs;
      trial.erase(trial.begin() + k);
      const size_t before = nonlinear_monomials(trial);
      const Polynomial r = Polynomial::constant(offset) + Polynomial::variable(y) * scale;
      for (auto& t : trial) t.p = substitute(t.p, x, r);
      if (nonlinear_monomials(trial) > before) continue;
      // y only where x = offset + scale y lies in x's domain.
      if (!zero_in(scale)) {
        const Interval allowed = (vars[x].domain - offset) / scale;
        if (!intersect(vars[y].domain, allowed, vars[y].domain))
          throw LinkageError(file, eq.line,
                             "the linkage cannot be assembled: '" + eq.name + "' puts " + vars[x].name +
                                 " outside its range");
      }
      eliminate(k, x, offset, y, scale);
      changed = true;
    }
  }
  return as;
}

}  // namespace

LinkageFormulation::LinkageFormulation(LinkageCase c, LinkageOptions options)
    : case_(std::move(c)), options_(options) {
  validate(case_);
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
      const LoopLink& e = loop.links[i];
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

  std::vector<Eq> eqs;
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
      const LoopLink& e = loop.links[i];
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
  std::vector<Eq> kept;
  for (auto& eq : eqs) {
    if (!eq.p.is_constant()) {
      kept.push_back(std::move(eq));
      continue;
    }
    const Interval k = eq.p.constant_term();
    if (!zero_in(k)) {
      std::ostringstream value;
      value << std::setprecision(3) << median(k);
      throw LinkageError(case_.file, eq.line,
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

  auto lph = std::make_shared<model::LphSystem>(to_lph(primary));
  sub_.label = "all";
  sub_.system = lph_polynomials(*lph, names);
  for (size_t v = 0; v < primary.variables.size(); ++v) sub_.split_dims.push_back(static_cast<int>(v));
  sub_.lph = std::move(lph);
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
