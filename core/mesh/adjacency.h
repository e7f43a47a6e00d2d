// Triangle adjacency across edges, built CSR-style from vertex stars.
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/util/result.h"

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
  size_t num_edges = 0;  ///< distinct undirected edges
  size_t num_nonmanifold_edges = 0;
  std::vector<int32_t> nonmanifold_example;  ///< one edge (a, b) if any
};

/// Only the vertex stars of the adjacency (star_offsets, star), by a
/// counting sort; `opposite` left empty.
TriangleAdjacency build_vertex_stars(const SurfaceMesh& mesh);

/// Builds the adjacency in time linear in the triangles for bounded vertex
/// degree (each edge is found once, by scanning one vertex star). Precondition: no triangle has a
/// repeated vertex.
TriangleAdjacency build_adjacency(const SurfaceMesh& mesh);

/// Updates `adj` after the triangles t with flipped[t] != 0 were reversed
/// by swapping their corners 1 and 2 (stars are unchanged).
void remap_after_flips(TriangleAdjacency& adj, const std::vector<uint8_t>& flipped);

/// Vertex 1-rings, CSR: the neighbors of v are ids[offsets[v] .. offsets[v + 1]).
struct VertexRings {
  std::vector<int32_t> offsets;  ///< num_vertices + 1
  std::vector<int32_t> ids;
};

/// The distinct neighbors of every vertex (through the triangles of its
/// star), each ring in the order its star first meets them.
VertexRings vertex_rings(const SurfaceMesh& m, const TriangleAdjacency& adj);

/// The structure the layers and the caps need of a wall: an error "the wall
/// has N non-manifold edges" or "the wall is not consistently oriented" (two
/// triangles run their shared edge the same way), else Ok.
Status check_manifold_oriented(const SurfaceMesh& wall, const TriangleAdjacency& adj);

/// Vertex a of half-edge h and vertex b (its end).
inline int32_t half_edge_from(const SurfaceMesh& m, int32_t h) { return m.triangles[h]; }
inline int32_t half_edge_to(const SurfaceMesh& m, int32_t h) {
  return m.triangles[h - h % 3 + (h % 3 + 1) % 3];
}

/// The half-edge of triangle t other than `not_this` that has vertex v as an
/// endpoint; -1 if none.
inline int32_t other_half_edge_at(const SurfaceMesh& m, int32_t t, int32_t v, int32_t not_this) {
  for (int k = 0; k < 3; ++k) {
    int32_t h = 3 * t + k;
    if (h == not_this) continue;
    if (half_edge_from(m, h) == v || half_edge_to(m, h) == v) return h;
  }
  return -1;
}

}  // namespace vm
