#include "core/mesh/adjacency.h"

namespace vm {

TriangleAdjacency build_adjacency(const SurfaceMesh& mesh) {
  TriangleAdjacency adj;
  const size_t nv = mesh.num_vertices();
  const size_t nt = mesh.num_triangles();
  const auto& tri = mesh.triangles;
  // Phase 1: vertex stars by counting sort.
  adj.star_offsets.assign(nv + 1, 0);
  for (int32_t v : tri) ++adj.star_offsets[v + 1];
  for (size_t v = 0; v < nv; ++v) adj.star_offsets[v + 1] += adj.star_offsets[v];
  adj.star.resize(tri.size());
  std::vector<int32_t> fill(adj.star_offsets.begin(), adj.star_offsets.end() - 1);
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) adj.star[fill[tri[3 * t + k]]++] = int32_t(t);

  // Phase 2: for each half-edge a->b, the other triangles of the star of a
  // that contain b.
  adj.opposite.assign(tri.size(), TriangleAdjacency::kBoundary);
  for (size_t t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      int32_t h = int32_t(3 * t + k);
      int32_t a = tri[h], b = half_edge_to(mesh, h);
      int32_t count = 1;
      int32_t other = -1;
      bool t_is_smallest = true;
      for (int32_t i = adj.star_offsets[a]; i < adj.star_offsets[a + 1]; ++i) {
        int32_t s = adj.star[i];
        if (size_t(s) == t) continue;
        for (int j = 0; j < 3; ++j) {
          if (tri[3 * s + j] != b) continue;
          // Edge {a, b} in s: find which of s's half-edges it is.
          int32_t ia = -1;
          for (int q = 0; q < 3; ++q)
            if (tri[3 * s + q] == a) ia = q;
          int32_t hs = (ia + 1) % 3 == j ? 3 * s + ia : 3 * s + j;
          ++count;
          other = hs;
          if (size_t(s) < t) t_is_smallest = false;
        }
      }
      if (count == 2) {
        adj.opposite[h] = other;
      } else if (count > 2) {
        adj.opposite[h] = TriangleAdjacency::kNonManifold;
      }
      if (t_is_smallest) {
        ++adj.num_edges;
        if (count > 2) {
          if (adj.num_nonmanifold_edges == 0) adj.nonmanifold_example = {a, b};
          ++adj.num_nonmanifold_edges;
        }
      }
    }
  }
  return adj;
}

}  // namespace vm
