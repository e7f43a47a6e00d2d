// Indexed triangle surface: the mesh type every surface stage reads and writes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vm {

/// A triangle surface as flat arrays.
/// - points: 3 * num_vertices() doubles, x y z of vertex i at [3i, 3i+3).
/// - triangles: 3 * num_triangles() vertex indices into points, counter-
///   clockwise seen from outside once oriented (normal = (b-a) x (c-a)).
struct SurfaceMesh {
  std::vector<double> points;
  std::vector<int32_t> triangles;

  size_t num_vertices() const { return points.size() / 3; }
  size_t num_triangles() const { return triangles.size() / 3; }
};

/// Axis-aligned bounding box of a point set; empty when min > max.
struct BoundingBox {
  double min[3] = {0, 0, 0};
  double max[3] = {0, 0, 0};
  double diagonal() const;
};

/// Bounding box of `points` (3 doubles per point). All zeros when empty.
BoundingBox bounding_box(const std::vector<double>& points);

}  // namespace vm
