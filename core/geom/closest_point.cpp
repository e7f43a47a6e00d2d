// Closest point on a triangle by Voronoi regions (Ericson 2005, 5.1.5).
#include "core/geom/closest_point.h"

#include "core/geom/vec3.h"

namespace vm {

using v3::dot;

double closest_point_on_triangle(const double* p, const double* a, const double* b, const double* c,
                                 double* out) {
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int k = 0; k < 3; ++k) {
    ab[k] = b[k] - a[k];
    ac[k] = c[k] - a[k];
    ap[k] = p[k] - a[k];
    bp[k] = p[k] - b[k];
    cp[k] = p[k] - c[k];
  }
  auto finish = [&](const double* base, const double* d1, double s, const double* d2, double t) {
    double d2sum = 0;
    for (int k = 0; k < 3; ++k) {
      out[k] = base[k] + s * d1[k] + t * d2[k];
      double e = p[k] - out[k];
      d2sum += e * e;
    }
    return d2sum;
  };
  const double zero[3] = {0, 0, 0};
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return finish(a, zero, 0, zero, 0);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return finish(b, zero, 0, zero, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double denom = d1 - d3;
    return finish(a, ab, denom > 0 ? d1 / denom : 0, zero, 0);
  }
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return finish(c, zero, 0, zero, 0);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double denom = d2 - d6;
    return finish(a, ac, denom > 0 ? d2 / denom : 0, zero, 0);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    double bc[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
    const double denom = (d4 - d3) + (d5 - d6);
    return finish(b, bc, denom > 0 ? (d4 - d3) / denom : 0, zero, 0);
  }
  const double sum = va + vb + vc;
  if (!(sum > 0)) return finish(a, zero, 0, zero, 0);  // degenerate: a vertex
  return finish(a, ab, vb / sum, ac, vc / sum);
}

}  // namespace vm
