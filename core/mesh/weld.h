// Welding an STL triangle soup into an indexed surface.
#pragma once

#include "core/io/stl.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

struct WeldOptions {
  /// Corners closer than tolerance * (bounding-box diagonal) become one
  /// vertex. 0 welds only bit-identical coordinates.
  double relative_tolerance = 1e-7;
};

struct WeldStats {
  size_t corners = 0;              ///< 3 * triangles in the soup
  size_t exact_unique = 0;         ///< distinct coordinates before tolerance merge
  size_t merged_by_tolerance = 0;  ///< distinct coordinates merged by tolerance
};

/// Merges coincident corners. Output vertices keep first-seen order; each
/// triangle keeps its corner order (it may become degenerate: see repair.h).
/// Runs in expected linear time (hash on exact bits, then a grid of cells of
/// the tolerance size for the near-coincident ones).
SurfaceMesh weld(const TriangleSoup& soup, const WeldOptions& options = {},
                 WeldStats* stats = nullptr);

}  // namespace vm
