// The core's small 3-vector: Vec3 (x y z as std::array) with its
// operators, and the same helpers over raw double pointers (3 doubles each)
// for the hot loops of the quality measures and the volume optimizer.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vm {

using Vec3 = std::array<double, 3>;

/// Point v of a flat point array (3 doubles per point).
inline Vec3 at(const std::vector<double>& pts, int32_t v) {
  return {pts[3 * size_t(v)], pts[3 * size_t(v) + 1], pts[3 * size_t(v) + 2]};
}
/// Sets point v of a flat point array.
inline void put(std::vector<double>& pts, int32_t v, const Vec3& p) {
  for (int k = 0; k < 3; ++k) pts[3 * size_t(v) + size_t(k)] = p[size_t(k)];
}
inline Vec3 operator+(const Vec3& a, const Vec3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Vec3 operator-(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec3 operator*(double s, const Vec3& a) { return {s * a[0], s * a[1], s * a[2]}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
/// "(x, y, z)" with 6 significant digits, for messages that say where.
std::string point_text(const Vec3& p);
/// A number for messages, with `digits` significant digits ("%g").
std::string number_text(double x, int digits = 4);

/// a / |a|, or a unchanged when it is zero.
inline Vec3 normalized(const Vec3& a) {
  const double n = norm(a);
  return n > 0 ? (1 / n) * a : a;
}

}  // namespace vm

namespace vm::v3 {

/// out = a - b.
inline void sub(const double* a, const double* b, double* out) {
  out[0] = a[0] - b[0], out[1] = a[1] - b[1], out[2] = a[2] - b[2];
}
/// out = u x v (out must not alias u or v).
inline void cross(const double* u, const double* v, double* out) {
  out[0] = u[1] * v[2] - u[2] * v[1];
  out[1] = u[2] * v[0] - u[0] * v[2];
  out[2] = u[0] * v[1] - u[1] * v[0];
}
inline double dot(const double* u, const double* v) {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}
inline double norm(const double* u) { return std::sqrt(dot(u, u)); }

}  // namespace vm::v3

namespace vm {

/// (b - a) x (c - a): the normal of triangle (a, b, c), twice its area long.
inline Vec3 triangle_cross(const double* a, const double* b, const double* c) {
  double u[3], w[3];
  Vec3 n;
  v3::sub(b, a, u);
  v3::sub(c, a, w);
  v3::cross(u, w, n.data());
  return n;
}

}  // namespace vm
