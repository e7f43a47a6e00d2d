// Safe repairs of a welded surface: degenerate and duplicate triangles,
// consistent orientation, outward orientation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/geom/vec3.h"
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
  /// One place of each kind of change, for the warnings: a removed
  /// degenerate triangle's centroid, a flat one's middle corner, a removed
  /// duplicate's centroid, a re-oriented triangle's centroid.
  Vec3 degenerate_example{}, collinear_example{}, duplicate_example{}, flipped_example{};
};

/// Removes triangles with a repeated vertex; removes flat triangles (three
/// distinct, exactly collinear corners) by splitting the neighbor across
/// their long edge at the middle corner, so no slit opens; removes duplicates
/// (same three vertices in any order); then drops the vertices no triangle
/// uses (renumbering, order kept). `labels` (one per triangle, or null)
/// follow their triangles; a triangle made by a split takes its neighbor's.
void remove_degenerate_and_duplicates(SurfaceMesh& mesh, RepairStats& stats,
                                      std::vector<int32_t>* labels = nullptr);

/// Removes the triangles t with remove[t] != 0 (and their labels, when
/// given: one per triangle) and the vertices left unused; returns the old ->
/// new vertex index map (-1 for a removed vertex). Triangle and vertex order
/// are kept.
std::vector<int32_t> remove_triangles(SurfaceMesh& mesh, const std::vector<uint8_t>& remove,
                                      std::vector<int32_t>* labels = nullptr);

/// Flips triangles so that every manifold edge is traversed in opposite
/// directions by its two triangles, per connected component, then orients
/// each component outward (positive enclosed volume, with openings closed by
/// a fan to each loop's centroid). Non-manifold edges do not propagate the
/// orientation. Precondition: no degenerate triangles. If `adjacency` is
/// given it receives the adjacency of the oriented mesh; with
/// `adjacency_is_current` it also holds build_adjacency(mesh) on entry
/// (used instead of building it again).
void orient_consistently(SurfaceMesh& mesh, RepairStats& stats,
                         TriangleAdjacency* adjacency = nullptr, bool adjacency_is_current = false);

}  // namespace vm
