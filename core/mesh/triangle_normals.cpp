// Triangle normals and areas (triangle_normals.h).
#include "core/mesh/triangle_normals.h"

#include "core/util/parallel.h"

namespace vm {

TriangleNormals triangle_normals(const SurfaceMesh& mesh) {
  const size_t nt = mesh.num_triangles();
  TriangleNormals out;
  out.normal.resize(nt);
  out.area.resize(nt);
  out.total_area = parallel_sum<double>(nt, size_t(1) << 16, [&](size_t begin, size_t end) {
    double sum = 0;
    for (size_t t = begin; t < end; ++t) {
      Vec3 n = triangle_cross(mesh, t);
      const double len = v3::norm(n.data());
      if (len > 0)
        for (double& x : n) x /= len;
      out.normal[t] = n;
      out.area[t] = 0.5 * len;
      sum += out.area[t];
    }
    return sum;
  });
  return out;
}

}  // namespace vm
