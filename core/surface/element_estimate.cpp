// Element counts from a size field (element_estimate.h).
#include "core/surface/element_estimate.h"

#include <cmath>

#include "core/geom/vec3.h"

namespace vm {

double estimate_triangles(const SurfaceMesh& m, const std::vector<double>& h) {
  double count = 0;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t* c = &m.triangles[3 * t];
    const double* a = &m.points[3 * size_t(c[0])];
    double u[3], w[3], n[3];
    v3::sub(&m.points[3 * size_t(c[1])], a, u);
    v3::sub(&m.points[3 * size_t(c[2])], a, w);
    v3::cross(u, w, n);
    const double size = (h[size_t(c[0])] + h[size_t(c[1])] + h[size_t(c[2])]) / 3;
    count += 0.5 * v3::norm(n) / (std::sqrt(3.0) / 4 * size * size);
  }
  return count;
}

double estimate_tetrahedra(double volume, double h) { return 9.4 * volume / (h * h * h); }

}  // namespace vm
