// Top-down BVH construction by median splits (Ericson, "Real-Time Collision
// Detection", 2005, section 6.2), iterative so deep trees cannot overflow the
// stack (the WebAssembly stack is small).
#include "core/mesh/triangle_bvh.h"

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "core/util/parallel.h"

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
  // centre along the longest side of their centres' box. The halves are the
  // same sets whatever selection algorithm runs (a total order), and the
  // numbering is the one of a depth-first build taking the right child
  // first and numbering a node's two children when it is split: a subtree
  // of c triangles splits internal(c) nodes, so the children of the
  // nodes below a right child start right after its parent's children,
  // and those below the left one 2 internal(right count) later. The top
  // splits run here, then the subtrees below them on the threads.
  struct Task {
    int32_t node, first, count, base;  // base: where the node's children go
  };
  auto internal = [leaf_size](int32_t c) {
    // Internal nodes of a subtree of c triangles, depth by depth: the sizes
    // at one depth differ by at most one, so each depth has at most two
    // (size, multiplicity) pairs.
    int32_t n = 0;
    std::vector<std::pair<int32_t, int32_t>> level = {{c, 1}}, next;
    while (!level.empty()) {
      next.clear();
      auto add = [&next](int32_t x, int32_t m) {
        for (auto& [y, k] : next)
          if (y == x) return void(k += m);
        next.push_back({x, m});
      };
      for (const auto& [x, m] : level)
        if (x > leaf_size) n += m, add(x / 2, m), add(x - x / 2, m);
      level.swap(next);
    }
    return n;
  };
  // Splits t (or makes it a leaf); returns its children's tasks (0 or 2).
  auto split = [&](const Task& t, Task* children) {
    if (t.count <= leaf_size) {
      // Within a leaf, by id (nth_element leaves each side in no set order).
      std::sort(items.begin() + t.first, items.begin() + t.first + t.count,
                [](const Item& a, const Item& b) { return a.id < b.id; });
      bvh.nodes[size_t(t.node)].first = t.first;
      bvh.nodes[size_t(t.node)].count = t.count;
      return 0;
    }
    double clo[3], chi[3];
    for (int d = 0; d < 3; ++d) {
      clo[d] = std::numeric_limits<double>::infinity();
      chi[d] = -std::numeric_limits<double>::infinity();
    }
    const auto begin = items.begin() + t.first;
    for (auto it = begin; it != begin + t.count; ++it)
      for (int d = 0; d < 3; ++d) {
        clo[d] = std::min(clo[d], it->c[d]);
        chi[d] = std::max(chi[d], it->c[d]);
      }
    int axis = 0;
    for (int d = 1; d < 3; ++d)
      if (chi[d] - clo[d] > chi[axis] - clo[axis]) axis = d;
    const int32_t half = t.count / 2;
    // A total order (ties by id): the same halves from every standard
    // library, so queries that meet equal distances pick the same triangle
    // natively and in WebAssembly.
    std::nth_element(begin, begin + half, begin + t.count, [axis](const Item& a, const Item& b) {
      return a.c[axis] != b.c[axis] ? a.c[axis] < b.c[axis] : a.id < b.id;
    });
    bvh.nodes[size_t(t.node)].first = t.base;
    bvh.nodes[size_t(t.node)].count = 0;
    children[0] = {t.base + 1, t.first + half, t.count - half, t.base + 2};
    children[1] = {t.base, t.first, half, t.base + 2 + 2 * internal(t.count - half)};
    return 2;
  };
  auto build_below = [&](const Task& root) {
    std::vector<Task> stack = {root};
    Task children[2];
    while (!stack.empty()) {
      const Task t = stack.back();
      stack.pop_back();
      const int n = split(t, children);
      for (int i = n; i-- > 0;) stack.push_back(children[i]);  // the right child first
    }
  };
  bvh.nodes.resize(size_t(1 + 2 * internal(int32_t(nt))));
  std::vector<Task> tasks = {{0, 0, int32_t(nt), 1}};
  const size_t wanted = 4 * size_t(thread_count());
  for (std::vector<Task> next; !tasks.empty() && tasks.size() < wanted && nt > 4096;) {
    next.clear();
    Task children[2];
    for (const Task& t : tasks) {
      const int n = split(t, children);
      next.insert(next.end(), children, children + n);
    }
    tasks.swap(next);
  }
  parallel_for(tasks.size(), 1, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) build_below(tasks[i]);
  });
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

bool split_leaf_pair_job(const TriangleBvh& bvh, LeafPairJob job, std::vector<LeafPairJob>& out) {
  const TriangleBvh::Node& A = bvh.nodes[size_t(job.a)];
  const TriangleBvh::Node& B = bvh.nodes[size_t(job.b)];
  const bool la = TriangleBvh::is_leaf(A), lb = TriangleBvh::is_leaf(B);
  if (job.a == job.b) {
    if (la) return false;
    out.push_back({A.first, A.first + 1});
    out.push_back({A.first + 1, A.first + 1});
    out.push_back({A.first, A.first});
    return true;
  }
  if (!boxes_overlap(A.lo, A.hi, B.lo, B.hi)) return true;
  if (la && lb) return false;
  auto extent = [](const TriangleBvh::Node& n) {
    return std::max({n.hi[0] - n.lo[0], n.hi[1] - n.lo[1], n.hi[2] - n.lo[2]});
  };
  if (lb || (!la && extent(A) >= extent(B))) {
    out.push_back({A.first + 1, job.b});
    out.push_back({A.first, job.b});
  } else {
    out.push_back({job.a, B.first + 1});
    out.push_back({job.a, B.first});
  }
  return true;
}

std::vector<LeafPairJob> leaf_pair_jobs(const TriangleBvh& bvh, size_t min_jobs) {
  std::vector<LeafPairJob> jobs, next;
  if (bvh.empty()) return jobs;
  jobs.push_back({});
  // A job's calls are one block of the traversal's, in the order of its
  // split: replacing every job by its split keeps the order.
  for (bool split = true; split && jobs.size() < min_jobs;) {
    split = false;
    next.clear();
    for (const LeafPairJob& job : jobs) {
      if (split_leaf_pair_job(bvh, job, next))
        split = true;
      else
        next.push_back(job);
    }
    jobs.swap(next);
  }
  return jobs;
}

}  // namespace vm
