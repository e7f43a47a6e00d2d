// Closing small defect holes of a surface: the hole's loop triangulated by
// ear clipping in its best-fit plane, then refined and relaxed after Liepa,
// "Filling holes in meshes" (Eurographics SGP 2003): triangles split at
// their centroids until their size matches the rim's edges, edges flipped
// to the Delaunay criterion, new vertices smoothed (umbrella operator).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm {

/// What filling one hole did.
struct HoleFill {
  bool filled = false;         ///< false: the loop was left open
  size_t triangles_added = 0;  ///< appended to the mesh's triangles
  size_t vertices_added = 0;   ///< appended to the mesh's points
  double min_angle = 0;        ///< smallest angle of the added triangles, degrees
};

/// Fills each loop of `loops` (vertex indices in order along the boundary
/// half-edges of an oriented surface, as boundary_loops gives them; 3 or
/// more vertices, each loop a simple cycle). The new triangles face the way
/// of their neighbors and take the label of the triangle on the loop's
/// first edge (`labels`: one per triangle, or null). A loop whose
/// triangulation would repeat an edge the surface already has between two
/// of its vertices is left open. Triangles and vertices are only appended.
std::vector<HoleFill> fill_holes(SurfaceMesh& mesh, const std::vector<std::vector<int32_t>>& loops,
                                 std::vector<int32_t>* labels = nullptr);

}  // namespace vm
