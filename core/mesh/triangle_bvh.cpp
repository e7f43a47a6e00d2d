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
  // Phase 1: per triangle its box and, beside its id, its box centre (the
  // split key); the splits reorder these records in place, so the median
  // searches read memory in order.
  std::vector<double> lo(3 * nt), hi(3 * nt);
  struct Item {
    double c[3];
    int32_t id;
  };
  std::vector<Item> items(nt);
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
      items[t].c[d] = 0.5 * (a + b);
    }
    items[t].id = int32_t(t);
  }
  // Phase 2: the tree, top-down: a node's triangles are split at the median
  // centre along the longest side of their centres' box.
  bvh.nodes.reserve(2 * (nt / size_t(leaf_size) + 1));
  bvh.nodes.emplace_back();
  struct Task {
    int32_t node, first, count;
  };
  std::vector<Task> stack = {{0, 0, int32_t(nt)}};
  while (!stack.empty()) {
    const Task task = stack.back();
    stack.pop_back();
    if (task.count <= leaf_size) {
      // Within a leaf, by id (nth_element leaves each side in no set order).
      std::sort(items.begin() + task.first, items.begin() + task.first + task.count,
                [](const Item& a, const Item& b) { return a.id < b.id; });
      bvh.nodes[size_t(task.node)].first = task.first;
      bvh.nodes[size_t(task.node)].count = task.count;
      continue;
    }
    double clo[3], chi[3];
    for (int d = 0; d < 3; ++d) {
      clo[d] = std::numeric_limits<double>::infinity();
      chi[d] = -std::numeric_limits<double>::infinity();
    }
    const auto begin = items.begin() + task.first;
    for (auto it = begin; it != begin + task.count; ++it)
      for (int d = 0; d < 3; ++d) {
        clo[d] = std::min(clo[d], it->c[d]);
        chi[d] = std::max(chi[d], it->c[d]);
      }
    int axis = 0;
    for (int d = 1; d < 3; ++d)
      if (chi[d] - clo[d] > chi[axis] - clo[axis]) axis = d;
    const int32_t half = task.count / 2;
    // A total order (ties by id): the same halves from every standard
    // library, so queries that meet equal distances pick the same triangle
    // natively and in WebAssembly.
    std::nth_element(begin, begin + half, begin + task.count, [axis](const Item& a, const Item& b) {
      return a.c[axis] != b.c[axis] ? a.c[axis] < b.c[axis] : a.id < b.id;
    });
    const int32_t left = int32_t(bvh.nodes.size());
    bvh.nodes[size_t(task.node)].first = left;
    bvh.nodes[size_t(task.node)].count = 0;
    bvh.nodes.emplace_back();
    bvh.nodes.emplace_back();
    stack.push_back({left, task.first, half});
    stack.push_back({left + 1, task.first + half, task.count - half});
  }
  bvh.order.resize(nt);
  for (size_t i = 0; i < nt; ++i) bvh.order[i] = items[i].id;
  // Phase 3: boxes, bottom-up (children come after their parent): a leaf's
  // from its triangles, an inner node's from its two children.
  for (size_t n = bvh.nodes.size(); n-- > 0;) {
    TriangleBvh::Node& node = bvh.nodes[n];
    for (int d = 0; d < 3; ++d) {
      node.lo[d] = std::numeric_limits<double>::infinity();
      node.hi[d] = -std::numeric_limits<double>::infinity();
    }
    if (TriangleBvh::is_leaf(node)) {
      for (int32_t i = node.first; i < node.first + node.count; ++i) {
        const size_t t = size_t(bvh.order[size_t(i)]);
        for (int d = 0; d < 3; ++d) {
          node.lo[d] = std::min(node.lo[d], lo[3 * t + d]);
          node.hi[d] = std::max(node.hi[d], hi[3 * t + d]);
        }
      }
    } else {
      for (const TriangleBvh::Node* child :
           {&bvh.nodes[size_t(node.first)], &bvh.nodes[size_t(node.first) + 1]})
        for (int d = 0; d < 3; ++d) {
          node.lo[d] = std::min(node.lo[d], child->lo[d]);
          node.hi[d] = std::max(node.hi[d], child->hi[d]);
        }
    }
  }
  return bvh;
}

}  // namespace vm
