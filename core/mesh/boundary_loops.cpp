#include "core/mesh/boundary_loops.h"

namespace vm {
namespace {

// Next boundary half-edge after `h` around vertex `v` (an endpoint of h),
// walking through the triangle fan of v; -1 if a non-manifold edge stops it.
int32_t next_by_fan(const SurfaceMesh& m, const TriangleAdjacency& adj, int32_t h, int32_t v) {
  int32_t cur = h;
  for (size_t guard = 0; guard < 1000000; ++guard) {
    int32_t g = other_half_edge_at(m, cur / 3, v, cur);
    if (g < 0) return -1;
    int32_t o = adj.opposite[g];
    if (o == TriangleAdjacency::kBoundary) return g;
    if (o == TriangleAdjacency::kNonManifold) return -1;
    cur = o;
  }
  return -1;
}

}  // namespace

std::vector<std::vector<int32_t>> boundary_loops(const SurfaceMesh& mesh,
                                                 const TriangleAdjacency& adj) {
  std::vector<std::vector<int32_t>> loops;
  const size_t nh = mesh.triangles.size();
  std::vector<uint8_t> visited(nh, 0);
  for (size_t h0 = 0; h0 < nh; ++h0) {
    if (adj.opposite[h0] != TriangleAdjacency::kBoundary || visited[h0]) continue;
    std::vector<int32_t> loop;
    int32_t h = int32_t(h0);
    int32_t v = half_edge_from(mesh, h);
    while (true) {
      visited[h] = 1;
      loop.push_back(v);
      // Walk on to the other end of h.
      int32_t a = half_edge_from(mesh, h), b = half_edge_to(mesh, h);
      v = a == v ? b : a;
      int32_t next = next_by_fan(mesh, adj, h, v);
      if (next < 0 || (visited[next] && next != int32_t(h0))) {
        // Fallback for non-manifold surroundings: any unvisited boundary
        // half-edge at v.
        next = -1;
        for (int32_t i = adj.star_offsets[v]; i < adj.star_offsets[v + 1]; ++i) {
          int32_t t = adj.star[i];
          for (int k = 0; k < 3 && next < 0; ++k) {
            int32_t g = 3 * t + k;
            if (adj.opposite[g] == TriangleAdjacency::kBoundary &&
                (!visited[g] || g == int32_t(h0)) &&
                (half_edge_from(mesh, g) == v || half_edge_to(mesh, g) == v))
              next = g;
          }
        }
      }
      if (next < 0 || next == int32_t(h0)) break;
      h = next;
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

}  // namespace vm
