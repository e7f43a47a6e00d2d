// Edge lengths of a triangle surface, per vertex.
#pragma once

#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm {

/// The mean length of the edges at each vertex of m (num_vertices values;
/// 0 for a vertex of no triangle). Interior edges count once per triangle,
/// i.e. twice, like boundary edges once: a local length scale, not an
/// exact mean over distinct edges.
std::vector<double> mean_edge_lengths(const SurfaceMesh& m);

}  // namespace vm
