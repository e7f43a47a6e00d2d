// Safe repairs of a welded surface: degenerate and duplicate triangles,
// consistent orientation, outward orientation.
#pragma once

#include <cstddef>

#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

struct RepairStats {
  size_t degenerate_removed = 0;  ///< repeated corner, or flat and unrepairable
  /// Flat triangles (distinct collinear corners) removed by splitting their
  /// neighbor across the long edge, which keeps the surface closed.
  size_t collinear_repaired = 0;
  size_t duplicates_removed = 0;  ///< same vertex set as an earlier triangle
  size_t flipped = 0;             ///< triangles reversed to orient consistently
  size_t unused_vertices_removed = 0;
  bool orientable = true;  ///< false if some component is non-orientable
};

/// Removes triangles with a repeated vertex; removes flat triangles (three
/// distinct, exactly collinear corners) by splitting the neighbor across
/// their long edge at the middle corner, so no slit opens; removes duplicates
/// (same three vertices in any order); then drops the vertices no triangle
/// uses (renumbering, order kept).
void remove_degenerate_and_duplicates(SurfaceMesh& mesh, RepairStats& stats);

/// Flips triangles so that every manifold edge is traversed in opposite
/// directions by its two triangles, per connected component, then orients
/// each component outward (positive enclosed volume, with openings closed by
/// a fan to each loop's centroid). Non-manifold edges do not propagate the
/// orientation. Precondition: no degenerate triangles. If `adjacency` is
/// given it receives the adjacency of the oriented mesh.
void orient_consistently(SurfaceMesh& mesh, RepairStats& stats,
                         TriangleAdjacency* adjacency = nullptr);

}  // namespace vm
