// The L/P/H vector model of a linkage (linkage.hpp): equations (1)-(4) over provisional
// variables, linear elimination, the joint limits, then the lifting to L/P/H.
#include "formulate/linkage.hpp"

#include "formulate/linear_elimination.hpp"
#include "formulate/to_lph.hpp"
#include "model/vector_algebra.hpp"
#include "interval/rigorous.hpp"

#include <algorithm>
#include <cstdio>
#include <iomanip>
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

using VecP = model::Vec3<Polynomial>;
using model::cross;
using model::dot;

const char* const axis_name[] = {".x", ".y", ".z"};

bool is_exact_zero(const Interval& x) { return x.lower() == 0 && x.upper() == 0; }

VecP constant_vector(const Interval& x, const Interval& y, const Interval& z) {
  return {Polynomial::constant(x), Polynomial::constant(y), Polynomial::constant(z)};
}

VecP minus(const VecP& u, const VecP& v) { return VecP{u[0] - v[0], u[1] - v[1], u[2] - v[2]}; }
VecP times(const VecP& u, const Interval& c) { return VecP{u[0] * c, u[1] * c, u[2] * c}; }

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

// Drops equations left constant (0 = 0 up to rounding); a non-zero constant is a
// contradiction already between ground and parameters.
std::vector<NamedEquation> drop_constant_equations(std::vector<NamedEquation>& eqs, const std::string& file) {
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
      throw input::InputError(file, eq.line,
                         "the linkage cannot be assembled: '" + eq.name + "' reduces to " + value.str() +
                             " = 0 (an overconstrained linkage closes only if its parameters satisfy its closure "
                             "condition exactly: write them as exact expressions such as \"pi/3\")");
    }
  }
  return kept;
}

// The system of `kept` over only the variables that occur in it, renumbered; index[v] is
// provisional variable v's number there (-1: it occurs in no equation).
model::System keep_occurring_variables(std::vector<NamedEquation>& kept, const std::vector<model::Variable>& vars,
                                       std::vector<int>& index) {
  index.assign(vars.size(), -1);
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
  return primary;
}

}  // namespace

// The model before elimination: provisional variables (the coordinates of the non-ground
// vectors, then the prismatic offsets), each vector and offset as a polynomial in them, and
// the equations over them. The steps run in the order build_model lists them.
class LinkageFormulation::ModelBuilder {
 public:
  explicit ModelBuilder(LinkageFormulation& f) : f_(f), joints_(static_cast<int>(f.joint_names_.size())) {}

  // Which normals the model needs: those in a loop closure (a != 0), next to a prismatic
  // joint (its theta relation), or whose twist may be 0 or pi (then (3) does not fix them).
  void choose_modelled_normals() {
    for (auto& nm : f_.normals_) {
      const Interval s = rigorous::sin(nm.alpha);
      nm.negative_sine = s.upper() < 0;
      nm.modelled = nm.ground || f_.options_.keep_free_normals || !is_exact_zero(nm.a) || zero_in(s);
    }
    for (size_t l = 0; l < f_.case_.loops.size(); ++l) {
      const size_t n = f_.case_.loops[l].links.size();
      for (size_t i = 0; i < n; ++i)
        if (f_.case_.loops[l].links[i].prismatic)
          f_.normals_[f_.loop_normals_[l][i]].modelled = f_.normals_[f_.loop_normals_[l][(i + n - 1) % n]].modelled =
              true;
    }
  }

  void add_provisional_variables() {
    vec_.resize(f_.vectors_.size());
    for (size_t v = 0; v < f_.vectors_.size(); ++v) {
      const bool is_axis = static_cast<int>(v) < joints_;
      if (f_.constant_[v]) {
        vec_[v] = constant_vector(f_.vectors_[v][0].value, f_.vectors_[v][1].value, f_.vectors_[v][2].value);
        continue;
      }
      if (!is_axis && !f_.normals_[v - joints_].modelled) continue;
      const std::string base = is_axis ? "d[" + f_.joint_names_[v] + "]" : f_.normals_[v - joints_].name;
      for (int k = 0; k < 3; ++k) {
        f_.vectors_[v][k].variable = static_cast<int>(vars_.size());
        vec_[v][k] = Polynomial::variable(static_cast<int>(vars_.size()));
        vars_.push_back({base + axis_name[k], Interval(-1.0, 1.0)});
      }
    }
    offset_.resize(joints_);
    for (auto& loop : f_.case_.loops)
      for (auto& e : loop.links) {
        if (!e.prismatic) continue;
        const int j = f_.joint_index_.at(e.joint);
        if (f_.offsets_[j].variable >= 0) continue;
        f_.offsets_[j].variable = static_cast<int>(vars_.size());
        offset_[j] = Polynomial::variable(static_cast<int>(vars_.size()));
        vars_.push_back({"offset[" + e.joint + "]", e.d});
      }
  }

  // (1) unit vectors.
  void add_unit_equations() {
    const Polynomial one = Polynomial::constant(Interval(1.0));
    std::vector<int> first_line(joints_, 0);
    for (auto& loop : f_.case_.loops)
      for (auto& e : loop.links) {
        const int j = f_.joint_index_.at(e.joint);
        if (!first_line[j]) first_line[j] = e.line;
      }
    for (int j = 0; j < joints_; ++j)
      eqs_.push_back({dot(vec_[j], vec_[j]) - one, "|d[" + f_.joint_names_[j] + "]| = 1", first_line[j]});
    for (size_t n = 0; n < f_.normals_.size(); ++n)
      if (f_.normals_[n].modelled)
        eqs_.push_back({dot(vec_[joints_ + n], vec_[joints_ + n]) - one, "|" + f_.normals_[n].name + "| = 1",
                        f_.normals_[n].line});
  }

  // (3), (4) per link between its two joints.
  void add_link_equations() {
    for (size_t n = 0; n < f_.normals_.size(); ++n) {
      const Normal& nm = f_.normals_[n];
      const VecP &din = vec_[nm.joint_in], &dout = vec_[nm.joint_out], &a = vec_[joints_ + n];
      const Interval s = rigorous::sin(nm.alpha), co = rigorous::cos(nm.alpha);
      eqs_.push_back({dot(din, dout) - Polynomial::constant(co), nm.name + ": d . d' = cos(alpha)", nm.line});
      if (!nm.modelled) continue;
      add3(minus(cross(din, dout), times(a, s)), nm.name + ": d x d' = sin(alpha) a", nm.line);
      if (zero_in(s)) {  // twist 0 or pi (or too close to tell): (3) leaves a free, pin it
        eqs_.push_back({dot(a, din), nm.name + ": a . d = 0", nm.line});
        eqs_.push_back({dot(a, dout), nm.name + ": a . d' = 0", nm.line});
      }
    }
  }

  // (2) loop closure; prismatic joints' theta relations.
  void add_closure_equations() {
    std::set<std::tuple<int, int, int>> prismatic_done;
    for (size_t l = 0; l < f_.case_.loops.size(); ++l) {
      const auto& loop = f_.case_.loops[l];
      const std::vector<int>& normal_at = f_.loop_normals_[l];
      const size_t n = loop.links.size();
      VecP sum;
      for (size_t i = 0; i < n; ++i) {
        const input::LoopLink& e = loop.links[i];
        const int j = f_.normals_[normal_at[i]].joint_in;
        const Polynomial length = e.prismatic ? offset_[j] : Polynomial::constant(e.d);
        for (int k = 0; k < 3; ++k) {
          sum[k] += length * vec_[j][k];
          if (!is_exact_zero(e.a)) sum[k] += vec_[joints_ + normal_at[i]][k] * e.a;
        }
        if (!e.prismatic) continue;
        const int prev = normal_at[(i + n - 1) % n], next = normal_at[i];
        if (!prismatic_done.insert({prev, j, next}).second) continue;
        const VecP &ap = vec_[joints_ + prev], &an = vec_[joints_ + next];
        const std::string name = "joint " + e.joint;
        eqs_.push_back(
            {dot(ap, an) - Polynomial::constant(rigorous::cos(e.theta)), name + ": a . a' = cos(theta)", e.line});
        add3(minus(cross(ap, an), times(vec_[j], rigorous::sin(e.theta))), name + ": a x a' = sin(theta) d", e.line);
      }
      add3(sum, "loop " + loop.name + ": closure", loop.line);
    }
  }

  // Angle constraints between axes.
  void add_angle_equations() {
    for (auto& ac : f_.case_.angle_constraints) {
      eqs_.push_back({dot(vec_[f_.joint_index_.at(ac.joint1)], vec_[f_.joint_index_.at(ac.joint2)]) -
                          Polynomial::constant(rigorous::cos(ac.angle)),
                      "angle " + (ac.name.empty() ? ac.joint1 + "," + ac.joint2 : ac.name) + ": d . d' = cos(angle)",
                      ac.line});
    }
  }

  // The system over the variables that survive elimination and occur in an equation; each
  // coordinate placed in it (place_coordinates).
  model::System primary_system() {
    const std::vector<Affine> elimination = eliminate_linear(eqs_, vars_, f_.case_.file);
    std::vector<NamedEquation> kept = drop_constant_equations(eqs_, f_.case_.file);
    std::vector<int> index;
    model::System primary = keep_occurring_variables(kept, vars_, index);
    place_coordinates(elimination, index);
    return primary;
  }

  // Joint limits: cos(h) |a_in| |a_out| - (a_in . a_out) cos(m) - ((a_in x a_out) . d) sin(m)
  // <= 0, where |a| is 1 for a modelled normal and |sin(alpha)| for one left out (its vector
  // is d_in x d_out there).
  void add_joint_limits(model::System& primary) {
    for (const input::JointLimit& jl : f_.case_.joint_limits) {
      const Interval lo(jl.lower.lower()), hi(jl.upper.upper()), pi = rigorous::pi();
      char bounds[64];
      std::snprintf(bounds, sizeof bounds, "[%.6g, %.6g]", median(jl.lower), median(jl.upper));
      Limit l{-1, (lo + hi) / Interval(2.0), (hi - lo) / Interval(2.0), jl.joint + " in " + bounds};
      if (l.half.upper() >= pi.lower()) continue;  // a full turn: no limit
      for (size_t k = 0; k < f_.outputs_.size() && l.output < 0; ++k)
        if (!f_.outputs_[k].turn && f_.outputs_[k].name == jl.joint) l.output = static_cast<int>(k);
      if (l.output < 0) throw std::logic_error("linkage: no output for limited joint " + jl.joint);
      const Output& o = f_.outputs_[l.output];
      const VecP d = f_.vector_polynomial(o.joint), ain = f_.vector_polynomial(joints_ + o.normal_in),
                 aout = f_.vector_polynomial(joints_ + o.normal_out);
      Interval scale(1.0);
      for (int n : {o.normal_in, o.normal_out})
        if (!f_.normals_[n].modelled) scale *= boost::numeric::abs(rigorous::sin(f_.normals_[n].alpha));
      model::Inequality g;
      g.g = Polynomial::constant(scale * rigorous::cos(l.half)) - dot(ain, aout) * rigorous::cos(l.mid) -
            dot(cross(ain, aout), d) * rigorous::sin(l.mid);
      g.name = "joint limit " + l.name;
      primary.inequalities.push_back(std::move(g));
      f_.limits_.push_back(std::move(l));
    }
  }

 private:
  void add3(const VecP& v, const std::string& name, int line) {
    for (int k = 0; k < 3; ++k) eqs_.push_back({v[k], name + " (" + std::string(axis_name[k] + 1) + ")", line});
  }

  // Coordinates: through the eliminations to a surviving variable or a constant; a variable
  // that occurs in no equation is unconstrained and stands for its domain.
  void place_coordinates(const std::vector<Affine>& elimination, const std::vector<int>& index) {
    auto place = [&](Coordinate& c) {
      if (c.variable < 0) return;
      const Affine& r = elimination[c.variable];
      if (r.variable >= 0 && index[r.variable] >= 0) {
        c = {index[r.variable], r.scale, r.offset};
      } else {
        const Interval free = r.variable >= 0 ? r.scale * vars_[r.variable].domain : Interval(0.0);
        c = {-1, Interval(1.0), r.offset + free};
      }
    };
    for (size_t v = 0; v < f_.vectors_.size(); ++v)
      for (auto& c : f_.vectors_[v]) place(c);
    for (auto& c : f_.offsets_) place(c);
  }

  LinkageFormulation& f_;
  const int joints_;
  std::vector<model::Variable> vars_;
  std::vector<VecP> vec_;          // by vector (axes, then normals); unset for a normal left out
  std::vector<Polynomial> offset_;  // by joint; prismatic joints only
  std::vector<NamedEquation> eqs_;
};

void LinkageFormulation::build_model() {
  ModelBuilder m(*this);
  m.choose_modelled_normals();
  m.add_provisional_variables();
  m.add_unit_equations();
  m.add_link_equations();
  m.add_closure_equations();
  m.add_angle_equations();
  model::System primary = m.primary_system();
  m.add_joint_limits(primary);

  auto lph = std::make_shared<model::LphSystem>(to_lph(primary));
  sub_.label = "all";
  sub_.system = lph_polynomials(*lph, primary.equation_names);
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

ModelSize LinkageFormulation::model_size() const {
  const model::LphSystem& s = *sub_.lph;
  const int primary = static_cast<int>(s.primary.size());
  return {primary, static_cast<int>(s.variables.size()) - primary, static_cast<int>(s.linear.size()),
          static_cast<int>(s.parabolic.size()), static_cast<int>(s.hyperbolic.size())};
}

}  // namespace linkbox::formulate
