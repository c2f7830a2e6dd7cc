#include "formulate/loop_closure.hpp"

#include "interval/rigorous.hpp"

namespace linkbox::formulate {

namespace {

using model::Polynomial;
using QPoly = std::array<Polynomial, 4>;  // (w, x, y, z)

Polynomial constant(double v) { return Polynomial::constant(Interval(v)); }

QPoly qmul(const QPoly& a, const QPoly& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

QPoly conjugate(const QPoly& q) { return {q[0], -q[1], -q[2], -q[3]}; }

// Q v Q* for a pure quaternion v: |Q|^2 times the rotated vector.
std::array<Polynomial, 3> rotate(const QPoly& q, const std::array<double, 3>& v) {
  const QPoly pv{Polynomial(), constant(v[0]), constant(v[1]), constant(v[2])};
  const QPoly r = qmul(qmul(q, pv), conjugate(q));
  return {r[1], r[2], r[3]};
}

}  // namespace

std::vector<model::Polynomial> dh_loop_closure(const LinkageLoop& loop, const std::vector<int>& variable,
                                               std::uint64_t chart) {
  const size_t n = loop.links.size();
  // |q_i|^2 for each entry (1 for prismatic joints, whose rotation is a constant).
  std::vector<Polynomial> norm2(n, constant(1));
  std::vector<QPoly> joint(n);
  for (size_t i = 0; i < n; ++i) {
    const LoopLink& l = loop.links[i];
    if (l.prismatic) {
      const Interval h = l.theta / Interval(2.0);
      joint[i] = {Polynomial::constant(rigorous::cos(h)), Polynomial(), Polynomial(), Polynomial::constant(rigorous::sin(h))};
      continue;
    }
    const Polynomial t = Polynomial::variable(variable[i]);
    joint[i] = {constant(1), Polynomial(), Polynomial(), t};
    if (chart >> variable[i] & 1) joint[i] = qmul(QPoly{Polynomial(), Polynomial(), Polynomial(), constant(1)}, joint[i]);
    norm2[i] = constant(1) + t * t;
  }
  // Products of the norms after entry i: suffix[i] = prod_{j >= i} |q_j|^2.
  std::vector<Polynomial> suffix(n + 1, constant(1));
  for (size_t i = n; i-- > 0;) suffix[i] = norm2[i] * suffix[i + 1];

  QPoly before{constant(1), Polynomial(), Polynomial(), Polynomial()};  // prod_{j<i} q_j c_j
  std::array<Polynomial, 3> position;
  for (size_t i = 0; i < n; ++i) {
    const LoopLink& l = loop.links[i];
    // Offset along z_{i-1} (the axis of joint i), rotated by everything before joint i.
    const Polynomial d = l.prismatic ? Polynomial::variable(variable[i]) : Polynomial::constant(l.d);
    if (!d.is_zero()) {
      auto z = rotate(before, {0, 0, 1});
      for (int k = 0; k < 3; ++k) position[k] += z[k] * d * suffix[i];
    }
    const QPoly upto = qmul(before, joint[i]);
    if (!(l.a.lower() == 0 && l.a.upper() == 0)) {
      auto x = rotate(upto, {1, 0, 0});
      for (int k = 0; k < 3; ++k) position[k] += x[k] * suffix[i + 1] * l.a;
    }
    const Interval h = l.alpha / Interval(2.0);
    before = qmul(upto, QPoly{Polynomial::constant(rigorous::cos(h)), Polynomial::constant(rigorous::sin(h)),
                              Polynomial(), Polynomial()});
  }
  std::vector<model::Polynomial> eqs{before[1], before[2], before[3]};
  for (auto& p : position) eqs.push_back(std::move(p));
  return eqs;
}

}  // namespace linkbox::formulate
