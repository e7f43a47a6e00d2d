// Triangle adjacency across edges, built CSR-style from vertex stars.
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm {

/// Half-edge h = 3 t + k is edge (tri[3t+k], tri[3t+(k+1)%3]) of triangle t.
struct TriangleAdjacency {
  /// Vertex -> incident triangles: star[star_offsets[v] .. star_offsets[v+1]).
  std::vector<int32_t> star_offsets;  ///< num_vertices + 1
  std::vector<int32_t> star;          ///< 3 * num_triangles
  /// Per half-edge: the opposite half-edge (3 t' + k') when exactly two
  /// triangles share the edge; kBoundary when only this triangle has it;
  /// kNonManifold when three or more triangles share it.
  std::vector<int32_t> opposite;  ///< 3 * num_triangles
  static constexpr int32_t kBoundary = -1;
  static constexpr int32_t kNonManifold = -2;
  size_t num_edges = 0;           ///< distinct undirected edges
  size_t num_nonmanifold_edges = 0;
  std::vector<int32_t> nonmanifold_example;  ///< one edge (a, b) if any
};

/// Builds the adjacency in O(sum of star sizes squared / star size), linear
/// for bounded vertex degree. Precondition: no triangle has a repeated vertex.
TriangleAdjacency build_adjacency(const SurfaceMesh& mesh);

/// Vertex a of half-edge h and vertex b (its end).
inline int32_t half_edge_from(const SurfaceMesh& m, int32_t h) {
  return m.triangles[h];
}
inline int32_t half_edge_to(const SurfaceMesh& m, int32_t h) {
  return m.triangles[h - h % 3 + (h % 3 + 1) % 3];
}

}  // namespace vm
