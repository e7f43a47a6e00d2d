// Boundary loops (the openings of a vessel surface) from the adjacency.
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

/// Each loop lists its vertices in order (first not repeated at the end),
/// traversed along the direction of its triangles' boundary half-edges, so
/// for an outward-oriented surface a cap closing the loop in reverse order
/// faces outward. At a bow-tie vertex (two boundary fans meeting) the walk
/// turns through the triangle fan, so each loop is a simple cycle.
std::vector<std::vector<int32_t>> boundary_loops(const SurfaceMesh& mesh,
                                                 const TriangleAdjacency& adj);

}  // namespace vm
