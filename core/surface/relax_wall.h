// Where the boundary layer cannot grow from a remeshed wall (a needle-like
// spike or a fold the wall follows from a noisy input: no direction sees all
// the triangles around a vertex, or no column height makes its prisms
// valid), the wall is relaxed there, locally: Taubin's lambda|mu filter
// (G. Taubin, "A signal processing approach to fair surface design",
// SIGGRAPH 1995), which smooths without shrinking, on the vertices near the
// places, the rest of the wall held. Used by the job to retry the layers.
#pragma once

#include <vector>

#include "core/geom/vec3.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

struct WallRelaxation {
  size_t vertices = 0;          ///< moved
  double max_displacement = 0;  ///< model units
  bool applied = false;         ///< false: nothing near, or the result crossed itself (undone)
};

/// Relaxes `wall` (manifold, oriented) with `passes` lambda|mu passes on
/// the vertices within `reach` (model units) of any of `places`, except
/// the vertices on openings (so caps stay planar); the other vertices do
/// not move. Undone (applied false) if a moved triangle then crosses the
/// wall. O(passes * moved vertices) plus one crossing test of the moved
/// triangles.
WallRelaxation relax_wall_near(SurfaceMesh& wall, const std::vector<Vec3>& places, double reach,
                               int passes = 10);

}  // namespace vm
