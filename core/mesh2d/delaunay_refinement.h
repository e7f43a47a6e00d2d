// Delaunay refinement of a planar domain to a size field: the "Delaunay" 2D
// mesher of the parameter plane (Marchandise et al., section 3, Table 1).
#pragma once

#include <functional>
#include <vector>

#include "core/mesh2d/constrained_delaunay.h"
#include "core/util/result.h"

namespace vm {

/// Target edge length at a point (u, v) of the plane; must be > 0.
using SizeField2D = std::function<double(double u, double v)>;

struct RefinementOptions {
  /// A triangle is too large when its longest edge exceeds this times the
  /// local size h.
  double size_tolerance = 1.4;
  /// A triangle is too poor when its smallest angle is below this (degrees)
  /// and its shortest edge is longer than half the local size.
  double min_angle_degrees = 28.0;
  /// Frontal mesher: a triangle is accepted when its circumradius is at
  /// most this times h / sqrt(3) (that of the equilateral triangle of side h).
  double frontal_radius_tolerance = 1.25;
  /// Safety limit on the number of vertices inserted.
  size_t max_inserted = 20'000'000;
};

/// Meshes the domain bounded by `segments` (as constrained_delaunay) by
/// inserting circumcenters of triangles that are too large for `size` or too
/// poorly shaped, in passes until none is left. The boundary is kept as
/// given: no point is added on a segment or inside a segment's diametral
/// circle, so patches that share a boundary discretization stay conforming
/// and the refinement terminates even when the size is finer than the
/// boundary. A circumcenter outside the domain, or
/// already tried for the same triangle, is replaced by the centroid, except
/// for triangles on the boundary, which are then accepted (their boundary
/// edge cannot be split). A
/// triangle on a boundary edge longer than the local size is judged against
/// that edge (the boundary cannot be refined), so a size field finer than
/// the boundary discretization still terminates.
/// Errors: those of constrained_delaunay, a non-positive size, or the safety
/// limit reached.
Result<Mesh2D> delaunay_refinement(const std::vector<double>& points,
                                   const std::vector<int32_t>& segments, const SizeField2D& size,
                                   const RefinementOptions& options = {});

}  // namespace vm
