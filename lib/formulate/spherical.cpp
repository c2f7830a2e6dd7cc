#include "formulate/spherical.hpp"

#include "formulate/half_angle.hpp"
#include "interval/rigorous.hpp"

#include <stdexcept>

namespace linkbox::formulate {

namespace {

using input::Factor;
using model::pure;
using model::qmul;

// Quaternion-valued multi-affine polynomial over the t variables of one loop:
// terms[mask] is the quaternion coefficient of prod_{j in mask} t_j.
using QuatPoly = std::vector<Quaternion>;

void times_constant(QuatPoly& p, const Quaternion& c) {
  for (auto& q : p) q = qmul(q, c);
}

// p <- p * (1 + t_j axis), t_j being local variable `bit`.
void times_joint(QuatPoly& p, size_t bit, const Vec3& axis) {
  const Quaternion a = pure(axis);
  for (size_t m = 0; m < p.size(); ++m)
    if (!(m & bit)) {
      const Quaternion add = qmul(p[m], a);
      for (int c = 0; c < 4; ++c) p[m | bit][c] += add[c];
    }
}

Quaternion factor_constant(const Factor& f) {
  return f.kind == Factor::Kind::constant ? f.q : axis_angle(f.axis, f.angle);
}

// Product of factors as a quaternion over a box of t values (shift: half-turn mask).
Quaternion evaluate_product(const std::vector<Factor>& factors, size_t shift, const Box& box) {
  Quaternion q{Interval(1.0), Interval(0.0), Interval(0.0), Interval(0.0)};
  for (auto& f : factors) {
    if (f.kind != Factor::Kind::joint) {
      q = qmul(q, factor_constant(f));
      continue;
    }
    const Vec3 p = normalized(f.axis);
    if (shift >> f.joint & 1) q = qmul(q, pure(p));
    const Interval& t = box[f.joint];
    q = qmul(q, Quaternion{Interval(1.0), t * p[0], t * p[1], t * p[2]});
  }
  return q;
}

bool contains_zero_everywhere(const model::Polynomial& p) {
  for (auto& [powers, c] : p.terms())
    if (!zero_in(c)) return false;
  return true;
}

}  // namespace

Vec3 normalized(const Vec3& v) {
  Interval n2 = square(v[0]) + square(v[1]) + square(v[2]);
  if (n2.lower() <= 0) throw std::invalid_argument("axis of zero length");
  Interval n = rigorous::sqrt(n2);
  return {v[0] / n, v[1] / n, v[2] / n};
}

Quaternion axis_angle(const Vec3& axis, const Interval& angle) {
  const Vec3 p = normalized(axis);
  const Interval half = angle / Interval(2.0);
  const Interval c = rigorous::cos(half), s = rigorous::sin(half);
  return {c, s * p[0], s * p[1], s * p[2]};
}

std::vector<std::vector<Interval>> rotation_matrix(const Quaternion& q) {
  const Interval &w = q[0], &x = q[1], &y = q[2], &z = q[3];
  const Interval n = square(w) + square(x) + square(y) + square(z), two(2.0);
  std::vector<std::vector<Interval>> r = {
      {square(w) + square(x) - square(y) - square(z), two * (x * y - w * z), two * (x * z + w * y)},
      {two * (x * y + w * z), square(w) - square(x) + square(y) - square(z), two * (y * z - w * x)},
      {two * (x * z - w * y), two * (y * z + w * x), square(w) - square(x) - square(y) + square(z)}};
  for (auto& row : r)
    for (auto& e : row) {
      e /= n;
      intersect(e, Interval(-1.0, 1.0), e);
    }
  return r;
}

SphericalFormulation::SphericalFormulation(input::SphericalCase c) : case_(std::move(c)) {
  input::validate(case_);
  for (size_t l = 0; l < case_.loops.size(); ++l) {
    LoopCache c;
    for (auto& f : case_.loops[l].factors)
      if (f.kind == Factor::Kind::joint) c.joints.push_back(f.joint);
    for (size_t local = 0; local < (size_t{1} << c.joints.size()); ++local) {
      size_t shift = 0;
      for (size_t b = 0; b < c.joints.size(); ++b) shift |= (local >> b & 1) << c.joints[b];
      c.by_local_shift.push_back(expand_loop(l, shift));
    }
    cache_.push_back(std::move(c));
  }
}

std::array<model::Polynomial, 3> SphericalFormulation::loop_equations(size_t loop, size_t shift) const {
  const LoopCache& c = cache_.at(loop);
  size_t local = 0;
  for (size_t b = 0; b < c.joints.size(); ++b) local |= (shift >> c.joints[b] & 1) << b;
  return c.by_local_shift[local];
}

std::array<model::Polynomial, 3> SphericalFormulation::expand_loop(size_t loop, size_t shift) const {
  const input::Loop& l = case_.loops.at(loop);
  std::vector<int> local;  // loop-local bit -> joint index
  for (auto& f : l.factors)
    if (f.kind == Factor::Kind::joint) local.push_back(f.joint);
  const Quaternion one{Interval(1.0), Interval(0.0), Interval(0.0), Interval(0.0)};
  QuatPoly p(size_t{1} << local.size(), Quaternion{Interval(0.0), Interval(0.0), Interval(0.0), Interval(0.0)});
  p[0] = one;
  size_t bit = 1;
  for (auto& f : l.factors) {
    if (f.kind != Factor::Kind::joint) {
      times_constant(p, factor_constant(f));
      continue;
    }
    const Vec3 axis = normalized(f.axis);
    // Half-turn shift (Section 3): rotating by phi + pi about p is p * q(phi).
    if (shift >> f.joint & 1) times_constant(p, pure(axis));
    times_joint(p, bit, axis);
    bit <<= 1;
  }
  std::array<model::Polynomial, 3> eqs;
  for (size_t m = 0; m < p.size(); ++m) {
    model::Polynomial mono = model::Polynomial::constant(Interval(1.0));
    for (size_t j = 0; j < local.size(); ++j)
      if (m >> j & 1) mono = mono * model::Polynomial::variable(local[j]);
    for (int c = 0; c < 3; ++c) eqs[c] += mono * p[m][c + 1];
  }
  return eqs;
}

SubProblem SphericalFormulation::subproblem(size_t index) const {
  SubProblem s;
  s.clipping = true;
  s.label = "shift ";
  for (size_t j = 0; j < case_.joints.size(); ++j) s.label += (index >> j & 1) ? '1' : '0';
  for (size_t j = 0; j < case_.joints.size(); ++j) {
    s.system.variables.push_back({"t_" + case_.joints[j].name, Interval(-1.0, 1.0)});
    s.split_dims.push_back(static_cast<int>(j));
  }
  static const char* comp[] = {"i", "j", "k"};
  for (size_t l = 0; l < case_.loops.size(); ++l) {
    auto eqs = loop_equations(l, index);
    for (int c = 0; c < 3; ++c) {
      // A component that vanishes identically (up to rounding) constrains nothing.
      if (contains_zero_everywhere(eqs[c])) continue;
      s.system.equations.push_back(std::move(eqs[c]));
      s.system.equation_names.push_back(case_.loops[l].name + "." + comp[c]);
    }
  }
  return s;
}

std::vector<std::string> SphericalFormulation::output_names() const {
  std::vector<std::string> n;
  for (auto& j : case_.joints) n.push_back(j.name);
  return n;
}

Box SphericalFormulation::to_output(size_t index, const Box& box) const { return tangents_to_angles(index, box); }

std::vector<MatrixOutput> SphericalFormulation::declared_outputs(size_t index, const Box& box) const {
  std::vector<MatrixOutput> r;
  for (auto& o : case_.outputs) r.push_back({o.name, rotation_matrix(evaluate_product(o.factors, index, box))});
  return r;
}

std::uint64_t SphericalFormulation::chart_for(const Box& output_hull) const { return half_turn_chart(output_hull); }

NaturalSystem SphericalFormulation::natural_system(std::uint64_t chart) const {
  SubProblem s = subproblem(chart);
  return {std::move(s.system.equations), s.system.names(), {}, {}, {}, nullptr, {}, {}, {}, {}};
}

Box SphericalFormulation::output_to_natural(std::uint64_t chart, const Box& output) const {
  return angles_to_tangents(chart, output);
}

}  // namespace linkbox::formulate
