// Star visibility of every vertex (see star_visibility.h).
#include "core/mesh/star_visibility.h"

#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"

namespace vm {

std::vector<double> star_visibility(const SurfaceMesh& mesh) {
  const size_t nv = mesh.num_vertices(), nt = mesh.num_triangles();
  const TriangleAdjacency stars = build_vertex_stars(mesh);
  // Unit triangle normals; their sums (area-weighted) per vertex.
  std::vector<double> unit(3 * nt), sum(3 * nv, 0.0);
  for (size_t t = 0; t < nt; ++t) {
    const int32_t* T = &mesh.triangles[3 * t];
    double u[3], w[3], n[3];
    v3::sub(&mesh.points[3 * size_t(T[1])], &mesh.points[3 * size_t(T[0])], u);
    v3::sub(&mesh.points[3 * size_t(T[2])], &mesh.points[3 * size_t(T[0])], w);
    v3::cross(u, w, n);
    const double len = v3::norm(n);
    for (int k = 0; k < 3; ++k) {
      unit[3 * t + size_t(k)] = len > 0 ? n[k] / len : 0;
      for (int c = 0; c < 3; ++c) sum[3 * size_t(T[c]) + size_t(k)] += n[k];
    }
  }
  constexpr double kTarget = 0.3;
  constexpr int kSteps = 20;
  std::vector<double> seen(nv, 1.0);
  for (size_t v = 0; v < nv; ++v) {
    const int32_t first = stars.star_offsets[v], count = stars.star_offsets[v + 1] - first;
    if (count == 0) continue;
    double d[3] = {sum[3 * v], sum[3 * v + 1], sum[3 * v + 2]};
    const double len = v3::norm(d);
    for (double& c : d) c = len > 0 ? c / len : 0;
    seen[v] = see_star(&stars.star[size_t(first)], count, unit.data(), d, kTarget, kSteps,
                       [](double*) {});
  }
  return seen;
}

}  // namespace vm
