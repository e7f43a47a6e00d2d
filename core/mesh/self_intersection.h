// Exact detection of self-intersections of a triangle surface: the check that
// a remeshed, capped surface is a valid boundary for the volume mesher
// (Marchandise et al., sections 2 and 2.2: the lumen must be a closed,
// non-intersecting surface before tetrahedra fill it).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm {

struct SelfIntersectionReport {
  /// Pairs of triangles that intersect other than at what they share by
  /// index (a common vertex or a common edge), i.e. crossing, touching or
  /// overlapping triangles.
  size_t pairs = 0;
  /// The first few of them, (t1, t2) with t1 < t2.
  std::vector<std::array<int32_t, 2>> examples;
  /// Triangles whose corners are exactly collinear (or coincide): skipped,
  /// since they have no plane; a valid surface has none.
  size_t degenerate_triangles = 0;
  /// Pairs whose boxes overlapped and were tested (a cost statistic).
  size_t tested_pairs = 0;
};

/// Finds every pair of non-degenerate triangles of `mesh` whose closed point
/// sets intersect beyond their shared vertices (by index): two triangles
/// sharing an edge intersect only if they are coplanar and fold onto each
/// other; sharing one vertex, only if the edge opposite it in one meets the
/// other triangle; sharing nothing, if they meet at all (touching counts);
/// sharing all three (a duplicate), always. Distinct vertices at the same
/// position are distinct: a surface touching itself there is reported.
/// Exact: every decision is the sign of orient3d / orient2d on the input
/// doubles (geom/predicates.h), so there is no tolerance. Candidates come
/// from a box hierarchy (mesh/triangle_bvh.h): O(n log n) for a surface with
/// well-shaped triangles. Keeps at most `max_examples` example pairs.
/// Precondition: indices in range.
SelfIntersectionReport find_self_intersections(const SurfaceMesh& mesh, size_t max_examples = 8);

/// The pairs that find_self_intersections would report with at least one
/// triangle flagged in `flagged` (one flag per triangle of `mesh`): those a
/// local change of the flagged triangles may have made. Cost: a hierarchy
/// over the flagged triangles and one query per triangle of the mesh.
SelfIntersectionReport find_self_intersections_of(const SurfaceMesh& mesh,
                                                  const std::vector<uint8_t>& flagged,
                                                  size_t max_examples = 8);

/// Flags for find_self_intersections_of after a change: per triangle of
/// `now`, 1 unless `before` has a triangle with the same three corner
/// positions (vertex numbers may differ, e.g. after a renumbering).
std::vector<uint8_t> changed_triangles(const SurfaceMesh& before, const SurfaceMesh& now);

/// The exact test of find_self_intersections for one pair of triangles t1,
/// t2 of `mesh` (sharing by index as above). False if either is degenerate.
bool triangles_intersect(const SurfaceMesh& mesh, int32_t t1, int32_t t2);

}  // namespace vm
