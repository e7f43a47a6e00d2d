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

/// A pair of nodes of a self-traversal (below): a == b pairs a node with
/// itself, else two disjoint subtrees.
struct LeafPairJob {
  int32_t a = 0, b = 0;
};

/// Expands `job` one level: the jobs it splits into, appended to `out` in
/// the order the traversal visits them. Returns false (nothing appended)
/// for a job that pairs leaves (f's calls themselves); a job whose boxes do
/// not overlap splits into nothing.
bool split_leaf_pair_job(const TriangleBvh& bvh, LeafPairJob job, std::vector<LeafPairJob>& out);

/// Jobs whose traversals, run one after the other in the order given,
/// make exactly the calls of for_each_leaf_pair(bvh, f) in its order: the
/// root's job split level by level until there are at least `min_jobs` (or
/// nothing left to split). For running the traversal on the threads, job
/// by job, and merging the results in job order. Empty for an empty tree.
std::vector<LeafPairJob> leaf_pair_jobs(const TriangleBvh& bvh, size_t min_jobs);

/// Calls f(i, j) once for every unordered pair of positions i != j of
/// bvh.order whose triangles lie in leaves with overlapping boxes, below
/// `job` (the candidates of a self-intersection test; the caller maps
/// positions to triangles through bvh.order and tests the triangles' own
/// boxes). A self-traversal: (n, n) pairs a node with itself, (a, b) two
/// disjoint subtrees, descending the larger box (by its longest side).
template <class F>
void for_each_leaf_pair(const TriangleBvh& bvh, LeafPairJob job, F&& f) {
  if (bvh.empty()) return;
  std::vector<LeafPairJob> stack = {job}, children;
  while (!stack.empty()) {
    job = stack.back();
    stack.pop_back();
    children.clear();
    if (split_leaf_pair_job(bvh, job, children)) {
      // Visited in order: pushed last to first.
      stack.insert(stack.end(), children.rbegin(), children.rend());
      continue;
    }
    const TriangleBvh::Node& A = bvh.nodes[size_t(job.a)];
    const TriangleBvh::Node& B = bvh.nodes[size_t(job.b)];
    if (job.a == job.b) {
      for (int32_t i = A.first; i < A.first + A.count; ++i)
        for (int32_t j = i + 1; j < A.first + A.count; ++j) f(i, j);
    } else {
      for (int32_t i = A.first; i < A.first + A.count; ++i)
        for (int32_t j = B.first; j < B.first + B.count; ++j) f(i, j);
    }
  }
}

/// for_each_leaf_pair() over the whole tree.
template <class F>
void for_each_leaf_pair(const TriangleBvh& bvh, F&& f) {
  for_each_leaf_pair(bvh, LeafPairJob{}, f);
}

}  // namespace vm
