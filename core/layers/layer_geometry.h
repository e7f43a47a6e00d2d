// Small geometry helpers shared by the boundary-layer phases (Marchandise et
// al., section 2.2): the vertex 1-rings of a triangle surface.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"

namespace vm::layers {

// The vector helpers are the core's (vm::Vec3, core/geom/vec3.h).
using vm::Vec3;

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
