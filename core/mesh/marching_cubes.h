// Marching cubes (Lorensen and Cline, "Marching cubes: a high resolution 3D
// surface construction algorithm", SIGGRAPH 1987) over a regular grid, slab
// by slab so that only two planes of values are held at once.
#pragma once

#include <cstddef>
#include <functional>

#include "core/mesh/surface_mesh.h"

namespace vm {

/// Regular grid: nx * ny * nz samples, sample (i, j, k) at
/// origin + spacing * (i, j, k).
struct GridSpec {
  int nx = 0, ny = 0, nz = 0;
  double origin[3] = {0, 0, 0};
  double spacing = 1.0;
};

/// Fills `plane` (nx * ny floats, index i + nx * j) with the field values of
/// plane k. Negative values are inside.
using PlaneFn = std::function<void(int k, float* plane)>;

/// Extracts the zero level set as a welded, closed (where the inside does not
/// touch the grid border), consistently oriented surface: triangle normals
/// point from inside (< 0) to outside (>= 0). Each grid edge crossing gets
/// one shared vertex; values closer to 0 than 1e-6 are moved to +1e-6 so no
/// vertex lands on a grid point. Ambiguous cube faces (inside corners on a
/// diagonal) are resolved by keeping the inside corners apart, a rule that
/// depends on the face alone, so neighboring cubes agree and the surface is
/// watertight. The case table is built once from these rules.
SurfaceMesh marching_cubes(const GridSpec& grid, const PlaneFn& plane_values);

}  // namespace vm
