// Optimization of a planar mesh after refinement: the smoothing and edge
// swaps that finish the seed's remeshing (Marchandise et al., section 2.1),
// done in the parameter plane so mapped-back points stay on the surface.
#pragma once

#include "core/mesh2d/constrained_delaunay.h"

namespace vm {

struct Optimize2DStats {
  size_t moves = 0;  ///< accepted vertex moves
  size_t flips = 0;  ///< edge flips
};

/// Alternates `passes` times: Delaunay flips of interior edges (the
/// boundary, i.e. edges with one triangle, never changes), then a Laplacian
/// move of each interior vertex to the centroid of its neighbors, accepted
/// only if all its triangles stay counterclockwise and the worst gamma of
/// its star does not drop. Vertices on the boundary never move. The result
/// covers the same domain with the same boundary edges. Precondition: `m`
/// is a valid counterclockwise triangulation (as produced by mesh2d).
Optimize2DStats optimize_mesh2d(Mesh2D& m, int passes = 5);

}  // namespace vm
