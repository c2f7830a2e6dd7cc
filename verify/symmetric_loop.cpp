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
using M44 = std::array<std::array<F, 4>, 4>;

F fast(const Interval& x) { return F(x.lower(), x.upper()); }
Interval safe(const F& x) { return Interval(x.lower(), x.upper()); }

M44 times(const M44& x, const M44& y) {
  M44 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      F s(0.0);
      for (int k = 0; k < 4; ++k) s += x[i][k] * y[k][j];
      r[i][j] = s;
    }
  return r;
}

std::array<F, 4> times(const std::array<F, 4>& a, const std::array<F, 4>& b) {
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
    s.a_[i] = fast(x.a);
    s.d_[i] = fast(x.d);
    s.cos_alpha_[i] = fast(rigorous::cos(x.alpha));
    s.sin_alpha_[i] = fast(rigorous::sin(x.alpha));
    s.cos_half_alpha_[i] = fast(rigorous::cos(x.alpha / 2.0));
    s.sin_half_alpha_[i] = fast(rigorous::sin(x.alpha / 2.0));
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

SymmetricLoop::Trig SymmetricLoop::trig(const Angles& theta) {
  Trig t;
  for (int i = 0; i < 3; ++i) {
    const fast_trig::SinCos sc = fast_trig::sin_cos(fast(theta[i]));
    t.c[i] = sc.cos;
    t.s[i] = sc.sin;
  }
  return t;
}

// The product of entries 0-2's transforms Rz(theta) Tz(d) Tx(a) Rx(alpha), or of their
// inverses in reverse order, with factor `derivative` replaced by its derivative in theta
// (whose last row is 0).
SymmetricLoop::M34 SymmetricLoop::chain(const Trig& t, int derivative, bool inverse) const {
  M44 product;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) product[i][j] = F(i == j ? 1.0 : 0.0);
  for (int step = 0; step < 3; ++step) {
    const int i = inverse ? 2 - step : step;
    const F &c = t.c[i], &s = t.s[i];
    const bool diff = derivative == i;
    // d/dtheta maps (c, s) to (-s, c) and drops the constant parts.
    const F c1 = diff ? -s : c, s1 = diff ? c : s, one(diff ? 0.0 : 1.0);
    const F &ca = cos_alpha_[i], &sa = sin_alpha_[i], &a = a_[i], &d = d_[i];
    const F z(0.0), zd = diff ? z : d, zd_sa = diff ? z : -d * sa, zd_ca = diff ? z : -d * ca,
                   za = diff ? z : -a;
    M44 m;
    if (!inverse)
      m = {{{c1, -s1 * ca, s1 * sa, c1 * a}, {s1, c1 * ca, -c1 * sa, s1 * a}, {z, diff ? z : sa, diff ? z : ca, zd},
            {z, z, z, one}}};
    else
      m = {{{c1, s1, z, za}, {-s1 * ca, c1 * ca, diff ? z : sa, zd_sa}, {s1 * sa, -c1 * sa, diff ? z : ca, zd_ca},
            {z, z, z, one}}};
    product = times(product, m);
  }
  M34 r;
  for (int i = 0; i < 3; ++i) r[i] = product[i];
  return r;
}

std::array<F, 4> SymmetricLoop::quaternion(const Trig& half, int derivative) const {
  std::array<F, 4> q{F(1.0), F(0.0), F(0.0), F(0.0)};
  const F z(0.0);
  for (int i = 0; i < 3; ++i) {
    const F &c = half.c[i], &s = half.s[i];
    const std::array<F, 4> about_z =
        derivative == i ? std::array<F, 4>{-s / 2.0, z, z, c / 2.0} : std::array<F, 4>{c, z, z, s};
    q = times(times(q, about_z), {cos_half_alpha_[i], sin_half_alpha_[i], z, z});
  }
  return q;
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
  const M34 t = chain(trig(first), -1, false), inv = chain(trig(second), -1, true);
  IVector d(12);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) d(4 * i + j) = safe(t[i][j] - inv[i][j]);
  return d;
}

IVector SymmetricLoop::a_values(const Box& uv) const {
  RoundingGuard guard;
  const auto [first, second] = halves(uv);
  const Trig a = trig(first), b = trig(second);
  const M34 ta = chain(a, -1, false), ia = chain(a, -1, true), tb = chain(b, -1, false), ib = chain(b, -1, true);
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
  const Trig a = trig(first), b = trig(second);
  IMatrix j(12, 3);
  for (int k = 0; k < 3; ++k) {
    const M34 ta = chain(a, k, false), ia = chain(a, k, true), tb = chain(b, k, false), ib = chain(b, k, true);
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 4; ++c) j(4 * i + c, k) = safe(ta[i][c] + ia[i][c] + sign * (tb[i][c] + ib[i][c]));
  }
  return j;
}

Interval SymmetricLoop::q0(const Box& u) const {
  RoundingGuard guard;
  return safe(quaternion(trig(halved(take(u, 0))), -1)[0]);
}

IVector SymmetricLoop::r_values(const Box& u) const {
  RoundingGuard guard;
  const auto th = take(u, 0);
  const auto q = quaternion(trig(halved(th)), -1);
  const M34 t = chain(trig(th), -1, false);
  IVector r(2);
  r(0) = safe(q[0]);
  r(1) = safe(q[1] * t[0][3] + q[2] * t[1][3] + q[3] * t[2][3]);
  return r;
}

IMatrix SymmetricLoop::r_jacobian(const Box& u) const {
  RoundingGuard guard;
  const auto th = take(u, 0);
  const Trig full = trig(th), half = trig(halved(th));
  const auto q = quaternion(half, -1);
  const M34 t = chain(full, -1, false);
  IMatrix j(2, 3);
  for (int k = 0; k < 3; ++k) {
    const auto dq = quaternion(half, k);
    const M34 dt = chain(full, k, false);
    j(0, k) = safe(dq[0]);
    j(1, k) = safe(dq[1] * t[0][3] + dq[2] * t[1][3] + dq[3] * t[2][3] + q[1] * dt[0][3] + q[2] * dt[1][3] +
                   q[3] * dt[2][3]);
  }
  return j;
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
  Box mid = uv;
  for (auto& x : mid) x = Interval(median(x));
  Box along_u = mid;  // U x {v^}
  for (int i = 0; i < 3; ++i) along_u[i] = uv[i];
  const IVector a0 = a_values(mid);
  const IMatrix ju = a_jacobian_u(along_u), jv = a_jacobian_v(uv);
  IVector rhs(12), offset(3);
  for (int row = 0; row < 12; ++row) {
    rhs(row) = a0(row);
    for (int k = 0; k < 3; ++k) rhs(row) += ju(row, k) * (uv[k] - mid[k]);
  }
  for (int r = 0; r < 3; ++r) offset(r) = uv[r + 3] - mid[r + 3];
  const Eigen::MatrixXd& c = choice.c;
  if (c.rows() != 3 || c.cols() != 12 || !c.allFinite()) return false;
  const IVector k = -newton::multiply(c, rhs) + newton::multiply(newton::identity_minus(c, jv), offset);
  for (int i = 0; i < 3; ++i) {
    const Interval image = mid[i + 3] + k(i);
    if (image.upper() < uv[i + 3].lower() || uv[i + 3].upper() < image.lower()) return true;
  }
  return false;
}

}  // namespace linkbox::verify
