// Constrained Delaunay triangulation of a planar straight-line graph: the
// kernel of the 2D meshers of the parameter plane (Marchandise et al.,
// section 2.1: the conformal map's image is meshed in 2D).
#pragma once

#include <cstdint>
#include <vector>

#include "core/util/result.h"

namespace vm {

/// A planar triangulation. points: 2 doubles per vertex; triangles: 3
/// vertex indices each, counterclockwise.
struct Mesh2D {
  std::vector<double> points;
  std::vector<int32_t> triangles;
  size_t num_vertices() const { return points.size() / 2; }
  size_t num_triangles() const { return triangles.size() / 3; }
};

/// Triangulates the domain bounded by `segments` (pairs of indices into
/// `points`, 2 doubles per point): every segment is a union of triangle
/// edges, every other edge is locally Delaunay (its opposite vertices are
/// not strictly inside each other's circumcircles), and only the regions
/// enclosed by an odd number of segment loops are kept (so a loop inside
/// another is a hole). With no segments the whole convex hull is
/// triangulated. Points keep their indices (duplicates are merged into the
/// first occurrence and unused by triangles). Uses exact predicates, so
/// degenerate input (cocircular grids, collinear points) is handled.
/// Errors: non-finite coordinates, a segment index out of range, segments
/// that cross each other.
Result<Mesh2D> constrained_delaunay(const std::vector<double>& points,
                                    const std::vector<int32_t>& segments);

}  // namespace vm
