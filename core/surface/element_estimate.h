// Element counts estimated from a size field before meshing, for the
// element budget (a run that would exhaust the memory of a browser tab is
// refused up front instead of failing after minutes).
#pragma once

#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm {

/// Triangles an isotropic mesh of `surface` at `vertex_size` (one target
/// edge length per vertex, > 0) has: the sum over the triangles of their
/// area over an equilateral triangle's of the mean size at their corners,
/// sqrt(3)/4 h^2.
double estimate_triangles(const SurfaceMesh& surface, const std::vector<double>& vertex_size);

/// Tetrahedra an isotropic mesh of a volume (model units cubed) at edge
/// length h has: 9.4 V / h^3, measured on vesselmesh's own meshes at
/// uniform sizes (9.2-9.4 on four real vessels); a size growing into the
/// core makes fewer.
double estimate_tetrahedra(double volume, double h);

}  // namespace vm
