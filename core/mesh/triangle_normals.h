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

/// (b - a) x (c - a) of triangle t (corners a, b, c): its normal, twice its
/// area long.
inline Vec3 triangle_cross(const SurfaceMesh& mesh, size_t t) {
  return triangle_cross(&mesh.points[3 * size_t(mesh.triangles[3 * t])],
                        &mesh.points[3 * size_t(mesh.triangles[3 * t + 1])],
                        &mesh.points[3 * size_t(mesh.triangles[3 * t + 2])]);
}

/// The normals and areas of every triangle of `mesh` (on the threads).
TriangleNormals triangle_normals(const SurfaceMesh& mesh);

}  // namespace vm
