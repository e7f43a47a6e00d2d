// Bounding-volume hierarchy of axis-aligned boxes over the triangles of a
// surface: the spatial search behind surface distances and self-intersection
// checks of the remeshed and capped surfaces (Marchandise et al., section 2:
// the output must stay on the input surface and be a valid boundary).
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm {

/// A binary tree of boxes. Node 0 is the root (absent for an empty mesh).
/// An inner node has count == 0 and children `first` and `first + 1`; a leaf
/// has count > 0 and holds triangles order[first .. first + count). Boxes
/// are the exact min/max of the corner coordinates of the triangles below
/// (no padding), so box tests are exact.
struct TriangleBvh {
  struct Node {
    double lo[3];
    double hi[3];
    int32_t first = 0;
    int32_t count = 0;
  };
  std::vector<Node> nodes;
  std::vector<int32_t> order;  ///< triangle ids, grouped by leaf

  bool empty() const { return nodes.empty(); }
  static bool is_leaf(const Node& n) { return n.count > 0; }
};

/// Builds the tree over all triangles of `mesh` by median splits of the
/// triangle centroids along the longest axis, leaves of at most `leaf_size`
/// (>= 1) triangles. O(n log n). The mesh must outlive queries (the tree
/// stores triangle ids, not coordinates).
TriangleBvh build_triangle_bvh(const SurfaceMesh& mesh, int leaf_size = 4);

/// True if the closed boxes [alo, ahi] and [blo, bhi] (3 doubles each) share
/// a point.
inline bool boxes_overlap(const double* alo, const double* ahi, const double* blo,
                          const double* bhi) {
  return alo[0] <= bhi[0] && blo[0] <= ahi[0] && alo[1] <= bhi[1] && blo[1] <= ahi[1] &&
         alo[2] <= bhi[2] && blo[2] <= ahi[2];
}

}  // namespace vm
