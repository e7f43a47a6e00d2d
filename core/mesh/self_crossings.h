// Where a surface crosses itself: the exact pairs of intersecting triangles
// (mesh/self_intersection.h) grouped into places, each located by a point
// of its crossing. A lumen must be a non-intersecting surface before it is
// meshed (Marchandise et al., sections 2 and 2.2); a segmentation whose wall
// is pushed through the opposite wall, or two branches fused wrongly, is not
// one, and the user fixes it there (docs/ARCHITECTURE.md, "Errors": say
// where).
#pragma once

#include <cstddef>
#include <vector>

#include "core/geom/vec3.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

struct SelfCrossings {
  /// Pairs of triangles that intersect beyond what they share by index
  /// (find_self_intersections' count).
  size_t pairs = 0;
  /// Places: groups of crossing triangles linked by a crossing pair or a
  /// shared vertex (one dent pushed through a wall is one place).
  size_t place_count = 0;
  /// One point per place, the largest places (most pairs) first, at most
  /// the `max_places` asked: the crossing point of the place's pair nearest
  /// the mean of its pairs' crossing points (model units).
  std::vector<Vec3> places;
};

/// Finds where `mesh` crosses itself. A pair's crossing point is the mean
/// of the points where the edges of either triangle pass through the other
/// (the ends of their intersection segment), in floating point; for
/// coplanar overlaps, the mean of the six corners. Places are formed from
/// the first `max_pairs` pairs found (the count of pairs is exact).
/// Cost: find_self_intersections' plus, when it finds pairs, O(pairs +
/// triangles + vertices). Precondition: indices in range.
SelfCrossings find_self_crossings(const SurfaceMesh& mesh, size_t max_places = 5,
                                  size_t max_pairs = 1'000'000);

}  // namespace vm
