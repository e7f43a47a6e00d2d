// Bounding-volume hierarchy of axis-aligned boxes over the triangles of a
// surface: the spatial search behind surface distances and self-intersection
// checks of the remeshed and capped surfaces (Marchandise et al., section 2:
// the output must stay on the input surface and be a valid boundary).
#pragma once

#include <algorithm>
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

/// Calls f(i, j) once for every unordered pair of positions i != j of
/// bvh.order whose triangles lie in leaves with overlapping boxes (the
/// candidates of a self-intersection test; the caller maps positions to
/// triangles through bvh.order and tests the triangles' own boxes). A
/// self-traversal: (n, n) pairs a node with itself, (a, b) two disjoint
/// subtrees, descending the larger box (by its longest side).
template <class F>
void for_each_leaf_pair(const TriangleBvh& bvh, F&& f) {
  if (bvh.empty()) return;
  struct Job {
    int32_t a, b;
  };
  std::vector<Job> stack = {{0, 0}};
  auto extent = [](const TriangleBvh::Node& n) {
    return std::max({n.hi[0] - n.lo[0], n.hi[1] - n.lo[1], n.hi[2] - n.lo[2]});
  };
  while (!stack.empty()) {
    const Job job = stack.back();
    stack.pop_back();
    const TriangleBvh::Node& A = bvh.nodes[size_t(job.a)];
    const TriangleBvh::Node& B = bvh.nodes[size_t(job.b)];
    if (job.a == job.b) {
      if (TriangleBvh::is_leaf(A)) {
        for (int32_t i = A.first; i < A.first + A.count; ++i)
          for (int32_t j = i + 1; j < A.first + A.count; ++j) f(i, j);
      } else {
        stack.push_back({A.first, A.first});
        stack.push_back({A.first + 1, A.first + 1});
        stack.push_back({A.first, A.first + 1});
      }
      continue;
    }
    if (!boxes_overlap(A.lo, A.hi, B.lo, B.hi)) continue;
    const bool la = TriangleBvh::is_leaf(A), lb = TriangleBvh::is_leaf(B);
    if (la && lb) {
      for (int32_t i = A.first; i < A.first + A.count; ++i)
        for (int32_t j = B.first; j < B.first + B.count; ++j) f(i, j);
      continue;
    }
    if (lb || (!la && extent(A) >= extent(B))) {
      stack.push_back({A.first, job.b});
      stack.push_back({A.first + 1, job.b});
    } else {
      stack.push_back({job.a, B.first});
      stack.push_back({job.a, B.first + 1});
    }
  }
}

}  // namespace vm
