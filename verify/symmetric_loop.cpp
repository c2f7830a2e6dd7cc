#include "verify/symmetric_loop.hpp"

#include "formulate/linkage.hpp"
#include "interval/fast_trig.hpp"
#include "interval/rigorous.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>

#include <cmath>

namespace linkbox::verify {

using newton::IMatrix;
using newton::IVector;

namespace {

using F = FastInterval;
F fast(const Interval& x) { return F(x.lower(), x.upper()); }
Interval safe(const F& x) { return Interval(x.lower(), x.upper()); }

template <class T>
std::array<T, 4> times(const std::array<T, 4>& a, const std::array<T, 4>& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

}  // namespace

std::optional<SymmetricLoop> SymmetricLoop::of(const formulate::Formulation& f) {
  const auto* linkage = dynamic_cast<const formulate::LinkageFormulation*>(&f);
  if (!linkage) return std::nullopt;
  const input::LinkageCase& c = linkage->linkage_case();
  if (c.loops.size() != 1 || !c.angle_constraints.empty() || !c.joint_limits.empty()) return std::nullopt;
  const auto& links = c.loops[0].links;
  const std::vector<std::string> names = f.output_names();
  if (links.size() != 6 || names.size() != 6) return std::nullopt;
  std::vector<int> output_of(6, -1);
  for (int i = 0; i < 6; ++i)
    for (int k = 0; k < 6; ++k)
      if (names[k] == links[i].joint) output_of[i] = k;
  return of_loop(*linkage, 0, output_of);
}

std::optional<SymmetricLoop> SymmetricLoop::of_loop(const formulate::LinkageFormulation& f, size_t loop,
                                                    const std::vector<int>& output_of) {
  const auto& links = f.linkage_case().loops.at(loop).links;
  const size_t outputs = f.output_names().size();
  if (links.size() != 6 || output_of.size() != 6) return std::nullopt;
  SymmetricLoop s;
  s.outputs_ = outputs;
  for (int i = 0; i < 6; ++i) {
    if (links[i].prismatic || output_of[i] < 0 || output_of[i] >= static_cast<int>(outputs)) return std::nullopt;
    s.output_of_[i] = output_of[i];
  }
  for (int i = 0; i < 3; ++i) {
    const auto &x = links[i], &y = links[i + 3];
    if (!input::same_link(x, y)) return std::nullopt;
    const Interval alpha(x.alpha), values[6] = {Interval(x.a),           Interval(x.d),
                                                rigorous::cos(alpha),    rigorous::sin(alpha),
                                                rigorous::cos(alpha / 2.0), rigorous::sin(alpha / 2.0)};
    std::array<F, 3>* fast_of[6] = {&s.p_.a, &s.p_.d, &s.p_.cos_alpha, &s.p_.sin_alpha, &s.p_.cos_half_alpha,
                                    &s.p_.sin_half_alpha};
    std::array<double, 3>* mid_of[6] = {&s.mid_.a, &s.mid_.d, &s.mid_.cos_alpha, &s.mid_.sin_alpha,
                                        &s.mid_.cos_half_alpha, &s.mid_.sin_half_alpha};
    for (int k = 0; k < 6; ++k) {
      (*fast_of[k])[i] = fast(values[k]);
      (*mid_of[k])[i] = median(values[k]);
    }
  }
  return s;
}

Box SymmetricLoop::to_uv(const Box& output) const {
  Box uv(6);
  for (int i = 0; i < 3; ++i) {
    const Interval& first = output.at(output_of_[i]);
    const Interval& second = output.at(output_of_[i + 3]);
    uv[i] = (first + second) / 2.0;
    uv[i + 3] = (first - second) / 2.0;
  }
  return uv;
}

Box SymmetricLoop::to_output(const Box& uv) const {
  Box out(outputs_);
  for (int i = 0; i < 3; ++i) {
    out[output_of_[i]] = uv.at(i) + uv.at(i + 3);
    out[output_of_[i + 3]] = uv.at(i) - uv.at(i + 3);
  }
  return out;
}

SymmetricLoop::Trig<F> SymmetricLoop::trig(const Angles& theta) {
  Trig<F> t;
  for (int i = 0; i < 3; ++i) {
    const fast_trig::SinCos sc = fast_trig::sin_cos(fast(theta[i]));
    t.c[i] = sc.cos;
    t.s[i] = sc.sin;
  }
  return t;
}

// Rows 0-2 of x y (only x's rows 0-2 enter them) for y whose row 3 is
// (0, 0, 0, y33), y33 exactly 1 or 0: the terms of row 3 are x[i][3] or exact zeros, so
// leaving them out of the sums changes no bound.
template <class T>
SymmetricLoop::M34<T> SymmetricLoop::affine_times(const M34<T>& x, const M34<T>& y, bool y33) {
  M34<T> r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) {
      T s = x[i][0] * y[0][j];
      s += x[i][1] * y[1][j];
      s += x[i][2] * y[2][j];
      if (j == 3 && y33) s += x[i][3];
      r[i][j] = s;
    }
  return r;
}

// The product of entries 0-2's transforms Rz(theta) Tz(d) Tx(a) Rx(alpha), or of their
// inverses in reverse order, with factor `derivative` replaced by its derivative in theta
// (whose last row is 0).
template <class T>
SymmetricLoop::M34<T> SymmetricLoop::chain(const Parameters<T>& p, const Trig<T>& t, int derivative, bool inverse) {
  M34<T> product;
  for (int step = 0; step < 3; ++step) {
    const int i = inverse ? 2 - step : step;
    const T &c = t.c[i], &s = t.s[i];
    const bool diff = derivative == i;
    // d/dtheta maps (c, s) to (-s, c) and drops the constant parts.
    const T c1 = diff ? T(-s) : c, s1 = diff ? c : s;
    const T &ca = p.cos_alpha[i], &sa = p.sin_alpha[i], &a = p.a[i], &d = p.d[i];
    const T z(0.0), zd = diff ? z : d, zd_sa = diff ? z : T(-d * sa), zd_ca = diff ? z : T(-d * ca),
                    za = diff ? z : T(-a);
    M34<T> m;
    if (!inverse)
      m = {{{c1, -s1 * ca, s1 * sa, c1 * a}, {s1, c1 * ca, -c1 * sa, s1 * a}, {z, diff ? z : sa, diff ? z : ca, zd}}};
    else
      m = {{{c1, s1, z, za}, {-s1 * ca, c1 * ca, diff ? z : sa, zd_sa}, {s1 * sa, -c1 * sa, diff ? z : ca, zd_ca}}};
    // Row 3 of m is (0, 0, 0, 1), or (0, 0, 0, 0) for the derivative's factor.
    product = step == 0 ? m : affine_times(product, m, !diff);
  }
  return product;
}

template <class T>
std::array<T, 4> SymmetricLoop::quaternion(const Parameters<T>& p, const Trig<T>& half, int derivative) {
  std::array<T, 4> q{T(1.0), T(0.0), T(0.0), T(0.0)};
  const T z(0.0);
  for (int i = 0; i < 3; ++i) {
    const T &c = half.c[i], &s = half.s[i];
    const std::array<T, 4> about_z =
        derivative == i ? std::array<T, 4>{T(-s / 2.0), z, z, T(c / 2.0)} : std::array<T, 4>{c, z, z, s};
    q = times(times(q, about_z), std::array<T, 4>{p.cos_half_alpha[i], p.sin_half_alpha[i], z, z});
  }
  return q;
}

template <class T>
void SymmetricLoop::r_and_jacobian(const Parameters<T>& p, const Trig<T>& full, const Trig<T>& half,
                                   std::array<T, 2>& r, std::array<std::array<T, 3>, 2>& j) {
  const auto q = quaternion(p, half, -1);
  const M34<T> t = chain(p, full, -1, false);
  r[0] = q[0];
  r[1] = q[1] * t[0][3] + q[2] * t[1][3] + q[3] * t[2][3];
  for (int k = 0; k < 3; ++k) {
    const auto dq = quaternion(p, half, k);
    const M34<T> dt = chain(p, full, k, false);
    j[0][k] = dq[0];
    j[1][k] = dq[1] * t[0][3] + dq[2] * t[1][3] + dq[3] * t[2][3] + q[1] * dt[0][3] + q[2] * dt[1][3] + q[3] * dt[2][3];
  }
}

namespace {

std::array<Interval, 3> take(const Box& b, int from) { return {b.at(from), b.at(from + 1), b.at(from + 2)}; }

std::array<Interval, 3> halved(std::array<Interval, 3> theta) {
  for (auto& x : theta) x = x / 2.0;
  return theta;
}

// theta = u + v (first half) and u - v (second half).
std::pair<std::array<Interval, 3>, std::array<Interval, 3>> halves(const Box& uv) {
  std::array<Interval, 3> first, second;
  for (int i = 0; i < 3; ++i) {
    first[i] = uv.at(i) + uv.at(i + 3);
    second[i] = uv.at(i) - uv.at(i + 3);
  }
  return {first, second};
}

}  // namespace

IVector SymmetricLoop::d_values(const Box& uv) const {
  RoundingGuard guard;
  const auto [first, second] = halves(uv);
  const M34<F> t = chain(p_, trig(first), -1, false), inv = chain(p_, trig(second), -1, true);
  IVector d(12);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) d(4 * i + j) = safe(t[i][j] - inv[i][j]);
  return d;
}

IVector SymmetricLoop::a_values(const Box& uv) const {
  RoundingGuard guard;
  const auto [first, second] = halves(uv);
  const Trig<F> a = trig(first), b = trig(second);
  const M34<F> ta = chain(p_, a, -1, false), ia = chain(p_, a, -1, true), tb = chain(p_, b, -1, false),
               ib = chain(p_, b, -1, true);
  IVector r(12);
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 4; ++c) r(4 * i + c) = safe(ta[i][c] + ia[i][c] - tb[i][c] - ib[i][c]);
  return r;
}

// A = T(u + v) + T(u + v)^-1 - T(u - v) - T(u - v)^-1: d/dv_k sums the four factors'
// derivatives (sign +1); d/du_k subtracts those at u - v (sign -1).
IMatrix SymmetricLoop::a_jacobian(const Box& uv, double sign) const {
  RoundingGuard guard;
  const auto [first, second] = halves(uv);
  const Trig<F> a = trig(first), b = trig(second);
  IMatrix j(12, 3);
  for (int k = 0; k < 3; ++k) {
    const M34<F> ta = chain(p_, a, k, false), ia = chain(p_, a, k, true), tb = chain(p_, b, k, false),
                 ib = chain(p_, b, k, true);
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 4; ++c) j(4 * i + c, k) = safe(ta[i][c] + ia[i][c] + sign * (tb[i][c] + ib[i][c]));
  }
  return j;
}

Interval SymmetricLoop::q0(const Box& u) const {
  RoundingGuard guard;
  return safe(quaternion(p_, trig(halved(take(u, 0))), -1)[0]);
}

IVector SymmetricLoop::r_values(const Box& u) const {
  RoundingGuard guard;
  const auto th = take(u, 0);
  const auto q = quaternion(p_, trig(halved(th)), -1);
  const M34<F> t = chain(p_, trig(th), -1, false);
  IVector r(2);
  r(0) = safe(q[0]);
  r(1) = safe(q[1] * t[0][3] + q[2] * t[1][3] + q[3] * t[2][3]);
  return r;
}

IMatrix SymmetricLoop::r_jacobian(const Box& u) const {
  RoundingGuard guard;
  const auto th = take(u, 0);
  std::array<F, 2> r;
  std::array<std::array<F, 3>, 2> dr;
  r_and_jacobian(p_, trig(th), trig(halved(th)), r, dr);
  IMatrix j(2, 3);
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 3; ++k) j(i, k) = safe(dr[i][k]);
  return j;
}

void SymmetricLoop::r_at(const Eigen::Vector3d& u, Eigen::Vector2d& r, Eigen::Matrix<double, 2, 3>& j) const {
  Trig<double> full, half;
  for (int i = 0; i < 3; ++i) {
    full.c[i] = std::cos(u(i));
    full.s[i] = std::sin(u(i));
    half.c[i] = std::cos(u(i) / 2);
    half.s[i] = std::sin(u(i) / 2);
  }
  std::array<double, 2> value;
  std::array<std::array<double, 3>, 2> d;
  r_and_jacobian(mid_, full, half, value, d);
  for (int i = 0; i < 2; ++i) {
    r(i) = value[i];
    for (int k = 0; k < 3; ++k) j(i, k) = d[i][k];
  }
}

Box toward_subspace(const Box& uv) {
  Box w = uv;
  for (int i = 3; i < 6; ++i) w[i] = hull(uv.at(i), Interval(0.0));
  return w;
}

std::optional<SymmetricLoop::RowChoice> SymmetricLoop::choose_rows(const Box& uv) const {
  Box centre(6);
  for (int i = 0; i < 6; ++i) centre[i] = Interval(i < 3 ? median(uv[i]) : 0.0);
  const Eigen::MatrixXd j = newton::midpoint(a_jacobian_v(centre));
  if (!j.allFinite()) return std::nullopt;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(j, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd s = svd.singularValues();
  if (!(s(2) > 1e-12 * s(0))) return std::nullopt;
  RowChoice best;
  best.c = svd.matrixV() * s.cwiseInverse().asDiagonal() * svd.matrixU().transpose();
  if (!best.c.allFinite()) return std::nullopt;
  return best;
}

bool SymmetricLoop::on_subspace(const Box& uv, const RowChoice& choice) const {
  const IMatrix j = a_jacobian_v(toward_subspace(uv));
  if (choice.c.rows() != 3 || choice.c.cols() != 12 || !choice.c.allFinite()) return false;
  return newton::norm_inf_upper(newton::identity_minus(choice.c, j)) < 1;
}

bool SymmetricLoop::excluded(const Box& uv, const RowChoice& choice) const {
  const Box mid = centre_box(uv);
  Box along_u = mid;  // U x {v^}
  for (int i = 0; i < 3; ++i) along_u[i] = uv[i];
  const IVector a0 = a_values(mid);
  const IMatrix ju = a_jacobian_u(along_u), jv = a_jacobian_v(uv);
  IVector rhs(12), offset(3);
  {
    RoundingGuard guard;  // the sums below in FastInterval: protected operations each switch the mode
    for (int row = 0; row < 12; ++row) {
      FastInterval s = as_fast(a0(row));
      for (int k = 0; k < 3; ++k) s += as_fast(ju(row, k)) * (as_fast(uv[k]) - as_fast(mid[k]));
      rhs(row) = as_protected(s);
    }
    for (int r = 0; r < 3; ++r) offset(r) = as_protected(as_fast(uv[r + 3]) - as_fast(mid[r + 3]));
  }
  const Eigen::MatrixXd& c = choice.c;
  if (c.rows() != 3 || c.cols() != 12 || !c.allFinite()) return false;
  const IVector cr = newton::multiply(c, rhs), step = newton::multiply(newton::identity_minus(c, jv), offset);
  RoundingGuard guard;
  for (int i = 0; i < 3; ++i) {
    const FastInterval image = as_fast(mid[i + 3]) + (as_fast(step(i)) - as_fast(cr(i)));
    if (image.upper() < uv[i + 3].lower() || uv[i + 3].upper() < image.lower()) return true;
  }
  return false;
}

}  // namespace linkbox::verify
