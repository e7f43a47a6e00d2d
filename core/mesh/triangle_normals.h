// Unit normals and areas of a surface's triangles, computed once for the
// preparation's tests that read them (the staircase test, the cap search).
#pragma once

#include <vector>

#include "core/geom/vec3.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

struct TriangleNormals {
  /// One per triangle: (b - a) x (c - a) normalized; zero for a zero-area
  /// triangle.
  std::vector<Vec3> normal;
  /// One per triangle: its area (model units squared).
  std::vector<double> area;
  /// The sum of `area`, added chunk by chunk (parallel.h).
  double total_area = 0;
};

/// The normals and areas of every triangle of `mesh` (on the threads).
TriangleNormals triangle_normals(const SurfaceMesh& mesh);

}  // namespace vm
