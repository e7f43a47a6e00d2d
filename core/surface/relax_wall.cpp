// Local relaxation of a wall for the boundary layer (relax_wall.h).
#include "core/surface/relax_wall.h"

#include <algorithm>

#include "core/mesh/adjacency.h"
#include "core/mesh/self_intersection.h"

namespace vm {

WallRelaxation relax_wall_near(SurfaceMesh& wall, const std::vector<Vec3>& places, double reach,
                               int passes) {
  WallRelaxation out;
  const size_t nv = wall.num_vertices();
  const TriangleAdjacency adj = build_adjacency(wall);
  const VertexRings rings = vertex_rings(wall, adj);
  std::vector<uint8_t> rim(nv, 0);
  for (size_t h = 0; h < adj.opposite.size(); ++h)
    if (adj.opposite[h] < 0) {
      rim[size_t(half_edge_from(wall, int32_t(h)))] = 1;
      rim[size_t(half_edge_to(wall, int32_t(h)))] = 1;
    }
  std::vector<int32_t> moving;
  for (size_t v = 0; v < nv; ++v) {
    if (rim[v]) continue;
    const Vec3 p = at(wall.points, int32_t(v));
    if (std::any_of(places.begin(), places.end(),
                    [&](const Vec3& q) { return norm(p - q) < reach; }))
      moving.push_back(int32_t(v));
  }
  if (moving.empty()) return out;
  const SurfaceMesh before = wall;
  std::vector<Vec3> next(moving.size());
  for (int pass = 0; pass < 2 * passes; ++pass) {
    const double factor = pass % 2 == 0 ? 0.5 : -0.53;  // lambda, then mu
    for (size_t i = 0; i < moving.size(); ++i) {
      const int32_t v = moving[i];
      const Vec3 p = at(wall.points, v);
      Vec3 mean{0, 0, 0};
      const int32_t b = rings.offsets[size_t(v)], e = rings.offsets[size_t(v) + 1];
      for (int32_t k = b; k < e; ++k) mean = mean + at(wall.points, rings.ids[size_t(k)]);
      mean = (1.0 / double(e - b)) * mean;
      next[i] = p + factor * (mean - p);
    }
    for (size_t i = 0; i < moving.size(); ++i) put(wall.points, moving[i], next[i]);
  }
  std::vector<uint8_t> moved_vertex(nv, 0), moved(wall.num_triangles(), 0);
  for (int32_t v : moving) moved_vertex[size_t(v)] = 1;
  for (size_t t = 0; t < moved.size(); ++t)
    for (int k = 0; k < 3; ++k) moved[t] |= moved_vertex[size_t(wall.triangles[3 * t + size_t(k)])];
  if (find_self_intersections_of(wall, moved, 1).pairs > 0) {
    wall = before;
    return out;
  }
  out.applied = true;
  out.vertices = moving.size();
  for (int32_t v : moving)
    out.max_displacement =
        std::max(out.max_displacement, norm(at(wall.points, v) - at(before.points, v)));
  return out;
}

}  // namespace vm
