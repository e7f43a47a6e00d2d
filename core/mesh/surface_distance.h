// Distances from points to a triangle surface, exact up to rounding (closest
// point on each candidate triangle, candidates from a box hierarchy): the
// check that a remeshed or capped surface stays on its input (Marchandise et
// al., section 2.1: every vertex of the new mesh lies on the input surface).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/mesh/triangle_bvh.h"

namespace vm {

/// The point of a surface closest to a query.
struct SurfacePoint {
  double distance = 0;            ///< Euclidean, model units
  int32_t triangle = -1;          ///< the triangle it lies on; -1 if the surface is empty
  std::array<double, 3> point{};  ///< x y z
};

/// Closest point of `surface` to q (3 doubles), searching `bvh` (built on
/// `surface` by build_triangle_bvh) branch and bound, nearest box first.
/// Degenerate triangles are handled (closest_point_on_triangle may then
/// return a point of the triangle that is not the closest on it, so the
/// distance is an upper bound there). Distance +inf for an empty surface.
SurfacePoint closest_surface_point(const SurfaceMesh& surface, const TriangleBvh& bvh,
                                   const double* q);

/// Summary of the distances of many points to a surface.
struct DistanceReport {
  double max = 0;     ///< largest distance (0 when there is no point)
  double mean = 0;    ///< mean distance
  size_t argmax = 0;  ///< index of the point at `max`
  size_t count = 0;   ///< number of query points
  /// Per query point (filled only when asked): count values.
  std::vector<double> per_point;
};

/// Distance of each point of `points` (3 doubles per point) to `surface`.
/// With `keep_per_point`, report.per_point holds each distance (e.g. to
/// compare with a local size h(x)). Cost: one tree build O(n log n) plus
/// O(log n) per query on well-shaped surfaces. Empty surface: distances are
/// +inf.
DistanceReport distances_to_surface(const SurfaceMesh& surface, const std::vector<double>& points,
                                    bool keep_per_point = false);
/// The same with `bvh` built on `surface` as it is (build_triangle_bvh).
DistanceReport distances_to_surface(const SurfaceMesh& surface, const TriangleBvh& bvh,
                                    const std::vector<double>& points, bool keep_per_point = false);

}  // namespace vm
