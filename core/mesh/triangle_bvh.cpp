// Top-down BVH construction by median splits (Ericson, "Real-Time Collision
// Detection", 2005, section 6.2), iterative so deep trees cannot overflow the
// stack (the WebAssembly stack is small).
#include "core/mesh/triangle_bvh.h"

#include <algorithm>
#include <limits>

namespace vm {

TriangleBvh build_triangle_bvh(const SurfaceMesh& mesh, int leaf_size) {
  TriangleBvh bvh;
  const size_t nt = mesh.num_triangles();
  if (nt == 0) return bvh;
  leaf_size = std::max(leaf_size, 1);
  // Per-triangle box and centroid.
  std::vector<double> lo(3 * nt), hi(3 * nt), centroid(3 * nt);
  for (size_t t = 0; t < nt; ++t) {
    for (int d = 0; d < 3; ++d) {
      double a = std::numeric_limits<double>::infinity(), b = -a;
      for (int k = 0; k < 3; ++k) {
        const double x = mesh.points[3 * size_t(mesh.triangles[3 * t + k]) + d];
        a = std::min(a, x);
        b = std::max(b, x);
      }
      lo[3 * t + d] = a;
      hi[3 * t + d] = b;
      centroid[3 * t + d] = 0.5 * (a + b);
    }
  }
  bvh.order.resize(nt);
  for (size_t t = 0; t < nt; ++t) bvh.order[t] = int32_t(t);
  bvh.nodes.reserve(2 * (nt / size_t(leaf_size) + 1));
  bvh.nodes.emplace_back();
  struct Task {
    int32_t node, first, count;
  };
  std::vector<Task> stack = {{0, 0, int32_t(nt)}};
  while (!stack.empty()) {
    const Task task = stack.back();
    stack.pop_back();
    // Box of the triangles and of their centroids.
    double blo[3], bhi[3], clo[3], chi[3];
    for (int d = 0; d < 3; ++d) {
      blo[d] = clo[d] = std::numeric_limits<double>::infinity();
      bhi[d] = chi[d] = -std::numeric_limits<double>::infinity();
    }
    for (int32_t i = task.first; i < task.first + task.count; ++i) {
      const size_t t = size_t(bvh.order[size_t(i)]);
      for (int d = 0; d < 3; ++d) {
        blo[d] = std::min(blo[d], lo[3 * t + d]);
        bhi[d] = std::max(bhi[d], hi[3 * t + d]);
        clo[d] = std::min(clo[d], centroid[3 * t + d]);
        chi[d] = std::max(chi[d], centroid[3 * t + d]);
      }
    }
    TriangleBvh::Node& node = bvh.nodes[size_t(task.node)];
    for (int d = 0; d < 3; ++d) node.lo[d] = blo[d], node.hi[d] = bhi[d];
    if (task.count <= leaf_size) {
      node.first = task.first;
      node.count = task.count;
      continue;
    }
    int axis = 0;
    for (int d = 1; d < 3; ++d)
      if (chi[d] - clo[d] > chi[axis] - clo[axis]) axis = d;
    const int32_t half = task.count / 2;
    auto begin = bvh.order.begin() + task.first;
    std::nth_element(begin, begin + half, begin + task.count, [&](int32_t a, int32_t b) {
      return centroid[3 * size_t(a) + size_t(axis)] < centroid[3 * size_t(b) + size_t(axis)];
    });
    const int32_t left = int32_t(bvh.nodes.size());
    bvh.nodes[size_t(task.node)].first = left;  // `node` may dangle after emplace_back
    bvh.nodes[size_t(task.node)].count = 0;
    bvh.nodes.emplace_back();
    bvh.nodes.emplace_back();
    stack.push_back({left, task.first, half});
    stack.push_back({left + 1, task.first + half, task.count - half});
  }
  return bvh;
}

}  // namespace vm
