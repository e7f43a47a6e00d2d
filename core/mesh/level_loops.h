// Level curves of a scalar field on a triangle surface (marching triangles):
// the field is given at the vertices and linear on each triangle; its curve
// at a value is traced across the triangles as ordered loops of points on the
// edges. Used for plane sections (the field is the signed distance to the
// plane) and for geodesic rings around a point.
//
// Ties are broken by a fixed rule (a simulation of simplicity): a vertex is
// "above" when f > value and "below" otherwise, so a vertex exactly at the
// value counts as below. Every triangle with vertices on both sides then has
// exactly two crossed edges, and the curves are disjoint simple chains of
// triangles: closed loops, or open curves ending at the surface's boundary.
// A vertex at the value is a curve point itself (possibly of several
// consecutive crossed edges).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

/// One level curve.
struct LevelLoop {
  /// Per point: the crossed edge as (below, above) vertex ids, f(below) <=
  /// value < f(above).
  std::vector<std::array<int32_t, 2>> edges;
  /// Per point: 3 coordinates, linearly interpolated on its edge (exactly the
  /// below vertex when f(below) == value).
  std::vector<double> points;
  /// triangles[i] is crossed from point i to point i + 1 (for a closed loop
  /// the last one returns to point 0; an open curve has one triangle fewer
  /// than points). Seen from outside (triangles counterclockwise), the
  /// "above" side is on the left of the walk.
  std::vector<int32_t> triangles;
  /// False when the curve ends at a boundary or non-manifold edge, or at a
  /// triangle outside the subset searched.
  bool closed = false;
  size_t size() const { return edges.size(); }
};

/// The level curves of `field` (one value per vertex; only the vertices of
/// the searched triangles are read) at `value`, over the triangles listed in
/// `triangles` (empty: all of them). `adj` is build_adjacency(mesh).
/// O(number of searched triangles + curve length x log).
std::vector<LevelLoop> level_loops(const SurfaceMesh& mesh, const TriangleAdjacency& adj,
                                   std::span<const double> field, double value,
                                   std::span<const int32_t> triangles = {});

/// Size and place of a polygon (3 coordinates a point).
struct CurveShape {
  std::array<double, 3> centroid{};  ///< edge midpoints weighted by edge length
  double perimeter = 0;
  /// Vector area of the closed polygon (sum of fan triangles from the
  /// centroid): its direction follows the walk by the right-hand rule.
  std::array<double, 3> vector_area{};
  double radius = 0;  ///< sqrt(|vector_area| / pi): the disk of the same area
  /// Smallest and largest distance of a point from the centroid.
  double min_distance = 0, max_distance = 0;
};

/// Measures the polygon `points` (closed: the last point joins the first).
CurveShape curve_shape(std::span<const double> points);

/// Winding number of the closed polygon `points` around `q`, both projected
/// along `normal` (unit) onto a plane: nonzero when q is inside.
int winding_number(std::span<const double> points, const std::array<double, 3>& q,
                   const std::array<double, 3>& normal);

/// Distance from q to the closed polygon `points` (its edges).
double distance_to_polygon(std::span<const double> points, const std::array<double, 3>& q);

}  // namespace vm
