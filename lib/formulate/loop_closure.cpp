#include "formulate/loop_closure.hpp"

#include "interval/rigorous.hpp"

namespace linkbox::formulate {

using model::Polynomial;
using model::conjugate;
using model::qmul;

namespace {

Polynomial constant(double v) { return Polynomial::constant(Interval(v)); }

// Q v Q* for a pure quaternion v: |Q|^2 times the rotated vector.
std::array<Polynomial, 3> rotate(const QuaternionPolynomial& q, const std::array<double, 3>& v) {
  const QuaternionPolynomial pv{Polynomial(), constant(v[0]), constant(v[1]), constant(v[2])};
  const QuaternionPolynomial r = qmul(qmul(q, pv), conjugate(q));
  return {r[1], r[2], r[3]};
}

}  // namespace

RotationFactor rotation_about_z(int variable, std::uint64_t chart) {
  const Polynomial t = Polynomial::variable(variable);
  QuaternionPolynomial q{constant(1), Polynomial(), Polynomial(), t};
  if (chart >> variable & 1) q = qmul(QuaternionPolynomial{Polynomial(), Polynomial(), Polynomial(), constant(1)}, q);
  return {q, constant(1) + t * t};
}

RotationFactor fixed_rotation_about_z(const Interval& theta) {
  const Interval h = theta / Interval(2.0);
  return {{Polynomial::constant(rigorous::cos(h)), Polynomial(), Polynomial(), Polynomial::constant(rigorous::sin(h))},
          constant(1)};
}

RotationFactor rotation_about_x(const Interval& alpha) {
  const Interval h = alpha / Interval(2.0);
  return {{Polynomial::constant(rigorous::cos(h)), Polynomial::constant(rigorous::sin(h)), Polynomial(), Polynomial()},
          constant(1)};
}

std::vector<model::Polynomial> dh_loop_closure(const input::LinkageLoop& loop, const std::vector<int>& variable,
                                               std::uint64_t chart) {
  const size_t n = loop.links.size();
  std::vector<RotationFactor> joint(n);
  for (size_t i = 0; i < n; ++i)
    joint[i] = loop.links[i].prismatic ? fixed_rotation_about_z(loop.links[i].theta) : rotation_about_z(variable[i], chart);
  // Products of the norms after entry i: suffix[i] = prod_{j >= i} |q_j|^2.
  std::vector<Polynomial> suffix(n + 1, constant(1));
  for (size_t i = n; i-- > 0;) suffix[i] = joint[i].norm2 * suffix[i + 1];

  QuaternionPolynomial before{constant(1), Polynomial(), Polynomial(), Polynomial()};  // prod_{j<i} q_j c_j
  std::array<Polynomial, 3> position;
  for (size_t i = 0; i < n; ++i) {
    const input::LoopLink& l = loop.links[i];
    // Offset along z_{i-1} (the axis of joint i), rotated by everything before joint i.
    const Polynomial d = l.prismatic ? Polynomial::variable(variable[i]) : Polynomial::constant(l.d);
    if (!d.is_zero()) {
      auto z = rotate(before, {0, 0, 1});
      for (int k = 0; k < 3; ++k) position[k] += z[k] * d * suffix[i];
    }
    const QuaternionPolynomial upto = qmul(before, joint[i].q);
    if (!(l.a.lower() == 0 && l.a.upper() == 0)) {
      auto x = rotate(upto, {1, 0, 0});
      for (int k = 0; k < 3; ++k) position[k] += x[k] * suffix[i + 1] * l.a;
    }
    before = qmul(upto, rotation_about_x(l.alpha).q);
  }
  std::vector<model::Polynomial> eqs{before[1], before[2], before[3]};
  for (auto& p : position) eqs.push_back(std::move(p));
  return eqs;
}

}  // namespace linkbox::formulate
