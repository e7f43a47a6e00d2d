// Sharp features of a surface that the remeshing keeps: creases such as the
// rims of flat caps already present in a closed input (Marchandise et al.,
// section 2.1: the surface is split into patches; patches end at creases so
// the conformal maps never flatten across one).
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

/// Per half-edge of `mesh` (3 per triangle): 1 if its edge is a sharp
/// feature, else 0 (both half-edges of a feature edge are flagged). An edge
/// is a candidate when the normals of its two triangles differ by more than
/// `angle_degrees`; candidates form chains, and a chain is kept only if it
/// does not dangle (it closes, or ends on an opening or another chain:
/// dangling ends are pruned edge by edge) and its component is at least
/// `min_length_factor` times the mean target size `h` (one per vertex)
/// long, so isolated sharp spots of segmentation noise are not features.
/// Empty result when angle_degrees >= 180.
std::vector<uint8_t> sharp_feature_edges(const SurfaceMesh& mesh, const TriangleAdjacency& adj,
                                         const std::vector<double>& h, double angle_degrees,
                                         double min_length_factor = 3.0);

}  // namespace vm
