// Small 3-vector helpers over raw double pointers (3 doubles each), for the
// hot loops of the quality measures and the volume optimizer.
#pragma once

#include <cmath>

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
