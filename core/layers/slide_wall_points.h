// Re-optimising the wall where boundary recovery split it (our own method):
// a Steiner point of the recovery (core/volume/boundary_recovery.h) on a
// wall edge, carried down the layers' columns (refine_layers.h) or on a
// wall without a viscous layer, splits the two wall triangles there at the
// edge's midpoint (or a shell distance), which can leave them far worse
// than the remeshed wall's. The point slides along its edge, with the
// points of its column along theirs, to where the wall triangles around it
// are best: the wall keeps its shape (the point stays on the edge), and
// only positions change, so the mesh stays conforming.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh/volume_mesh.h"

namespace vm {

/// A wall point on a wall edge and the points of its layer column, each on
/// the segment between the same two columns' points on its layer: 3 ids
/// per point (the point, the segment's ends a and b), the wall point first.
/// All move together, p = a + t (b - a), with one t.
struct WallPointColumn {
  std::vector<int32_t> points;
};

struct SlideStats {
  size_t moved = 0;           ///< columns moved
  double wall_min = 1;        ///< smallest gamma_k around the columns' wall points, before
  double wall_min_after = 1;  ///< and after
};

/// Slides each column (in order) to the t in [0.2, 0.8] (41 samples, and
/// the current) that maximises the smallest gamma_k of the triangles of
/// `m` tagged `wall_tag` around its wall point, keeping every tetrahedron
/// and prism that touches a moved point strictly positive (exact; a
/// prism's three smallest-index tetrahedra) and the smallest gamma_t of
/// those tetrahedra no lower than it was. A column moves only when its
/// wall's smallest gamma_k rises. Precondition: ids in range; the prisms'
/// tetrahedra are split_prism's.
SlideStats slide_wall_points(VolumeMesh& m, const std::vector<WallPointColumn>& columns,
                             int32_t wall_tag);

}  // namespace vm
