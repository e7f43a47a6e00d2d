// gamma_k = 2 r_in / r_circ (Marchandise et al., section 3), computed from
// the edge lengths: r_in = 2A / (a + b + c), r_circ = a b c / (4A), so
// gamma = 16 A^2 / (a b c (a + b + c)).
#include "core/geom/triangle_gamma.h"

#include <algorithm>
#include <cmath>

namespace vm {

double triangle_gamma(const double* a, const double* b, const double* c) {
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = b[k] - a[k];
    v[k] = c[k] - a[k];
    w[k] = c[k] - b[k];
  }
  double cx = u[1] * v[2] - u[2] * v[1];
  double cy = u[2] * v[0] - u[0] * v[2];
  double cz = u[0] * v[1] - u[1] * v[0];
  double area2 = cx * cx + cy * cy + cz * cz;  // (2A)^2
  double la = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  double lb = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  double lc = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  double den = la * lb * lc * (la + lb + lc);
  if (!(den > 0)) return 0.0;
  // 16 A^2 = 4 (2A)^2.
  return std::clamp(4.0 * area2 / den, 0.0, 1.0);
}

}  // namespace vm
