// Welding an STL triangle soup (triangle_soup.h), or the indexed points of
// another surface format, into an indexed surface.
#pragma once

#include "core/mesh/surface_mesh.h"
#include "core/mesh/triangle_soup.h"

namespace vm {

struct WeldOptions {
  /// Corners closer than tolerance * (bounding-box diagonal) become one
  /// vertex. 0 welds only bit-identical coordinates.
  double relative_tolerance = 1e-7;
  /// ... and never farther apart than this fraction of the median edge, so
  /// that a far stray point, which inflates the bounding box, cannot
  /// collapse the surface.
  double edge_fraction = 1e-4;
};

struct WeldStats {
  size_t corners = 0;              ///< 3 * triangles in the soup
  size_t exact_unique = 0;         ///< distinct coordinates before tolerance merge
  size_t merged_by_tolerance = 0;  ///< distinct coordinates merged by tolerance
};

/// Merges coincident corners. Output vertices keep first-seen order; each
/// triangle keeps its corner order (it may become degenerate: see repair.h).
/// Runs in expected linear time (hash on exact bits, then a grid of cells of
/// the tolerance size for the near-coincident ones). An ASCII soup (indexed
/// doubles) is welded as an indexed surface (below).
SurfaceMesh weld(const TriangleSoup& soup, const WeldOptions& options = {},
                 WeldStats* stats = nullptr);

/// The same, freeing the soup's coordinates (the largest array of the
/// input) as soon as the distinct points are taken from them, so that the
/// rest of the weld reuses that memory; `soup` is left without triangles.
SurfaceMesh weld(TriangleSoup&& soup, const WeldOptions& options = {}, WeldStats* stats = nullptr);

/// The same for an indexed surface as the non-STL readers give it (see
/// surface_file.h): points (3 doubles each) that are bit-identical (-0 and
/// +0 alike) become one vertex, then points closer than the tolerance
/// (relative to the bounding-box diagonal of the used points). Points no
/// triangle uses are dropped. Vertices come in order of first use by a
/// corner, so the result equals the soup weld of the same triangles when the
/// coordinates are floats; triangles keep their order and corner order.
/// stats->corners is triangles.size(), exact_unique the distinct used points.
/// Precondition: triangles.size() % 3 == 0 and every index is in
/// [0, points.size() / 3).
SurfaceMesh weld(const std::vector<double>& points, const std::vector<int32_t>& triangles,
                 const WeldOptions& options = {}, WeldStats* stats = nullptr);

}  // namespace vm
