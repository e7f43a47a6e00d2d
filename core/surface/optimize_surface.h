// Global optimization of the assembled surface mesh: edge swaps and
// smoothing with projection onto the input surface (Marchandise et al.,
// section 2.1, last step), which also heals the seams between patches.
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

struct SurfaceOptimizeOptions {
  int passes = 10;  ///< swap + smoothing passes
  /// A swap or a move is refused if it turns a triangle's normal by more
  /// than this (degrees), so the mesh cannot fold over sharp features.
  double max_normal_turn_degrees = 25;
};

struct SurfaceOptimizeStats {
  size_t swaps = 0;
  size_t moves = 0;
};

/// Improves `mesh` in place: swaps an interior edge when the smaller gamma_k
/// of its two triangles increases, and moves each vertex not `fixed` to the
/// mean of the apexes that would make its triangles equilateral, projected
/// onto `input` (the closest point found
/// by a walk from `home[v]`, an input triangle near v, which is updated)
/// when the smallest gamma_k of its star increases, or stays and the star's
/// mean increases. Vertices only move to
/// points of the input surface; the boundary edges of `mesh` never change.
/// Preconditions: `mesh` is manifold and consistently oriented, home has
/// one input triangle per vertex, fixed one flag per vertex, input_adj is
/// build_adjacency(input).
SurfaceOptimizeStats optimize_on_surface(SurfaceMesh& mesh, std::vector<int32_t>& home,
                                         const std::vector<uint8_t>& fixed,
                                         const SurfaceMesh& input,
                                         const TriangleAdjacency& input_adj,
                                         const SurfaceOptimizeOptions& options = {});

/// The point of `input` closest to q (3 doubles) among the triangles reached
/// by a walk from triangle `start` over triangles no farther than `start`;
/// writes it to `out` and returns its triangle.
int32_t project_near(const double* q, int32_t start, const SurfaceMesh& input,
                     const TriangleAdjacency& input_adj, double* out);

}  // namespace vm
