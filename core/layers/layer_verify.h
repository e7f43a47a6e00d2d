// Verification of the boundary layer (Marchandise et al., section 2.2:
// "prevent element overlap in regions of tight corners"): with every
// sub-tetrahedron positive, a layer whose closed boundary (wall, front,
// rings) does not intersect itself is embedded (no two elements overlap).
#pragma once

#include <cstdint>
#include <vector>

#include "core/layers/layer_columns.h"
#include "core/layers/layer_mesh.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

/// Tests exactly (triangles_intersect, with exact orient3d shortcuts for
/// neighbors) every pair of the layer's closed boundary that involves a
/// front or ring triangle: the wall, the front (layer `layers` of `cols`
/// with `factor`), and the faces the prisms have in each opening's plane,
/// split by the smallest-index diagonals as the prisms are (pairs within the
/// wall are the input's business and are not tested). Returns the wall
/// vertex ids of the columns of every front or ring triangle that meets
/// another triangle beyond what they share (repeats possible; empty: the
/// boundary is embedded). O(n log n): one hierarchy over the front and
/// rings, a self-traversal for their pairs and one query per wall triangle.
std::vector<int32_t> layer_intersections(const SurfaceMesh& wall, const LayerColumns& cols,
                                         const std::vector<double>& factor, int layers,
                                         const std::vector<LayerOpening>& ops, bool outward);

}  // namespace vm
