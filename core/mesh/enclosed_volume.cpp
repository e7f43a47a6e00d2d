// Divergence theorem on a closed triangulated surface: the volume is the sum
// of the signed volumes of the tetrahedra joining a fixed point to every
// triangle (see enclosed_volume.h).
#include "core/mesh/enclosed_volume.h"

#include <cmath>

#include "core/mesh/triangle_normals.h"

namespace vm {

double enclosed_volume(const SurfaceMesh& mesh) {
  if (mesh.num_triangles() == 0) return 0.0;
  const BoundingBox box = bounding_box(mesh.points);
  const double o[3] = {0.5 * (box.min[0] + box.max[0]), 0.5 * (box.min[1] + box.max[1]),
                       0.5 * (box.min[2] + box.max[2])};
  double sum = 0;
  for (size_t t = 0; t < mesh.num_triangles(); ++t) {
    double p[3][3];
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d)
        p[k][d] = mesh.points[3 * size_t(mesh.triangles[3 * t + k]) + d] - o[d];
    sum += p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) +
           p[0][1] * (p[1][2] * p[2][0] - p[1][0] * p[2][2]) +
           p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
  }
  return sum / 6.0;
}

double surface_area(const SurfaceMesh& mesh) {
  double sum = 0;
  for (size_t t = 0; t < mesh.num_triangles(); ++t) {
    const Vec3 n = triangle_cross(mesh, t);
    sum += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  return sum;
}

}  // namespace vm
