// Small geometry helpers shared by the boundary-layer phases (Marchandise et
// al., section 2.2): 3-vectors over flat point arrays and the vertex
// 1-rings of a triangle surface.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"

namespace vm::layers {

using Vec3 = std::array<double, 3>;

inline Vec3 at(const std::vector<double>& pts, int32_t v) {
  return {pts[3 * size_t(v)], pts[3 * size_t(v) + 1], pts[3 * size_t(v) + 2]};
}
inline void put(std::vector<double>& pts, int32_t v, const Vec3& p) {
  for (int k = 0; k < 3; ++k) pts[3 * size_t(v) + size_t(k)] = p[k];
}
inline Vec3 operator+(const Vec3& a, const Vec3& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Vec3 operator-(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec3 operator*(double s, const Vec3& a) { return {s * a[0], s * a[1], s * a[2]}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
/// a / |a|, or a unchanged when it is zero.
inline Vec3 normalized(const Vec3& a) {
  const double n = norm(a);
  return n > 0 ? (1 / n) * a : a;
}

/// Vertex 1-rings, CSR: the neighbors of v are ids[offsets[v] .. offsets[v + 1]).
struct VertexRings {
  std::vector<int32_t> offsets;  ///< num_vertices + 1
  std::vector<int32_t> ids;
};

/// The distinct neighbors of every vertex (through the triangles of its star).
inline VertexRings vertex_rings(const SurfaceMesh& m, const TriangleAdjacency& adj) {
  const size_t nv = m.num_vertices();
  VertexRings r;
  r.offsets.assign(nv + 1, 0);
  std::vector<int32_t> scratch;
  for (size_t v = 0; v < nv; ++v) {
    scratch.clear();
    for (int32_t i = adj.star_offsets[v]; i < adj.star_offsets[v + 1]; ++i) {
      const int32_t* t = &m.triangles[3 * size_t(adj.star[size_t(i)])];
      for (int k = 0; k < 3; ++k)
        if (size_t(t[k]) != v) {
          bool seen = false;
          for (int32_t u : scratch) seen = seen || u == t[k];
          if (!seen) scratch.push_back(t[k]);
        }
    }
    r.ids.insert(r.ids.end(), scratch.begin(), scratch.end());
    r.offsets[v + 1] = int32_t(r.ids.size());
  }
  return r;
}

}  // namespace vm::layers
