#pragma once
// 3-vectors and quaternions over any ring: intervals (rigorous constants and enclosures) or
// polynomials (loop equations). One definition of the products, whatever the entries are;
// a default-constructed T must be the ring's zero (Boost intervals: [0, 0]; Polynomial: 0).
#include <array>

namespace linkbox::model {

template <class T>
using Vec3 = std::array<T, 3>;
template <class T>
using Quaternion = std::array<T, 4>;  // (w, x, y, z)

template <class T>
T dot(const Vec3<T>& u, const Vec3<T>& v) {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

template <class T>
Vec3<T> cross(const Vec3<T>& u, const Vec3<T>& v) {
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

template <class T>
Quaternion<T> qmul(const Quaternion<T>& a, const Quaternion<T>& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

template <class T>
Quaternion<T> conjugate(const Quaternion<T>& q) {
  return {q[0], -q[1], -q[2], -q[3]};
}

// The pure quaternion (0, v).
template <class T>
Quaternion<T> pure(const Vec3<T>& v) {
  return {T{}, v[0], v[1], v[2]};
}

}  // namespace linkbox::model
