// Conforming refinement of a boundary layer to a refined wall or front
// triangulation (Marchandise et al., section 2.2: the lumen's core is
// meshed after the layer, bounded by its front). Boundary recovery of the
// core (volume/boundary_recovery.h) may split front triangles by Steiner
// points on their edges; the layer's prisms must then be split the same way
// through all their layers down to the wall (and an outward layer on the
// same wall split again to match the refined wall), or the mesh would not
// conform.
#pragma once

#include <cstdint>
#include <vector>

#include "core/layers/layer_mesh.h"
#include "core/util/result.h"

namespace vm {

/// Rebuilds `m` over a refinement of its wall triangulation, given as
/// column ids: id < m.wall_vertices is one of m's columns, id = nv + j a
/// new column j.
/// - triangles: 3 column ids per triangle, oriented like the wall; together
///   they tile m's wall triangles (each refined triangle inside its parent).
/// - parent: per triangle, the wall triangle of m it lies in.
/// - new_points: 3 doubles per new column: its exact position on layer
///   `at_layer` (0: a point of the wall, e.g. the wall refined for another
///   layer; m.layers: a point of the front, e.g. a Steiner point of the
///   core's recovery), on an edge or inside of its parent triangle there.
/// A new column's other points are the same barycentric combination (of its
/// parent's corners, measured on layer at_layer, clamped to the triangle and
/// snapped to an edge within 1e-9) of its parent's column points on each
/// layer; on layer at_layer it is new_points exactly. A new column on a rim
/// edge joins that opening's rim and columns (in the cap plane, since it
/// interpolates two in-plane columns). Per-vertex arrays are interpolated
/// (directions renormalized).
/// The result numbers points like any LayerMesh with nv' = nv + new columns:
/// layer k of column v is k nv' + v. So the core's front vertex v < nv is now
/// m'.layer_vertex(v, N), and new column j's front point is
/// m'.layer_vertex(nv + j, N).
/// Errors: malformed input (sizes, ids, parents), a new column shared by
/// triangles of parents with no common edge or vertex, a sub-tetrahedron of
/// the refined prisms that is not strictly positive (exact orient3d).
Result<LayerMesh> refine_layer_columns(const LayerMesh& m, const std::vector<int32_t>& triangles,
                                       const std::vector<int32_t>& parent,
                                       const std::vector<double>& new_points, int at_layer);

}  // namespace vm
