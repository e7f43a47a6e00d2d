#include "core/mesh/triangle_bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include "core/util/parallel.h"
#include "tests/support/icosphere.h"

namespace vm {
namespace {

// The tree by its definition, one node at a time: split at the median of
// the box centres (ties by id) along the longest side of their box, the
// left half the smaller; a node's two children numbered when it is split,
// the right subtree before the left; leaves list their triangles by id.
TriangleBvh reference_bvh(const SurfaceMesh& m, int leaf_size) {
  struct Item {
    double c[3];
    int32_t id;
  };
  const size_t nt = m.num_triangles();
  std::vector<Item> items(nt);
  std::vector<double> lo(3 * nt), hi(3 * nt);
  for (size_t t = 0; t < nt; ++t) {
    for (int d = 0; d < 3; ++d) {
      double a = std::numeric_limits<double>::infinity(), b = -a;
      for (int k = 0; k < 3; ++k) {
        const double x = m.points[3 * size_t(m.triangles[3 * t + size_t(k)]) + size_t(d)];
        a = std::min(a, x), b = std::max(b, x);
      }
      lo[3 * t + size_t(d)] = a, hi[3 * t + size_t(d)] = b;
      items[t].c[d] = 0.5 * (a + b);
    }
    items[t].id = int32_t(t);
  }
  TriangleBvh bvh;
  bvh.nodes.emplace_back();
  struct Task {
    int32_t node, first, count;
  };
  std::vector<Task> stack = {{0, 0, int32_t(nt)}};
  while (!stack.empty()) {
    const Task t = stack.back();
    stack.pop_back();
    const auto begin = items.begin() + t.first, end = begin + t.count;
    if (t.count <= leaf_size) {
      std::sort(begin, end, [](const Item& a, const Item& b) { return a.id < b.id; });
      bvh.nodes[size_t(t.node)].first = t.first;
      bvh.nodes[size_t(t.node)].count = t.count;
      continue;
    }
    int axis = 0;
    double ext[3];
    for (int d = 0; d < 3; ++d) {
      const auto [mn, mx] = std::minmax_element(
          begin, end, [d](const Item& a, const Item& b) { return a.c[d] < b.c[d]; });
      ext[d] = mx->c[d] - mn->c[d];
      if (ext[d] > ext[axis]) axis = d;
    }
    std::sort(begin, end, [axis](const Item& a, const Item& b) {
      return a.c[axis] != b.c[axis] ? a.c[axis] < b.c[axis] : a.id < b.id;
    });
    const int32_t left = int32_t(bvh.nodes.size()), half = t.count / 2;
    bvh.nodes[size_t(t.node)].first = left;
    bvh.nodes[size_t(t.node)].count = 0;
    bvh.nodes.resize(bvh.nodes.size() + 2);
    stack.push_back({left, t.first, half});
    stack.push_back({left + 1, t.first + half, t.count - half});
  }
  for (const Item& it : items) bvh.order.push_back(it.id);
  for (size_t n = bvh.nodes.size(); n-- > 0;) {
    TriangleBvh::Node& node = bvh.nodes[n];
    std::fill(node.lo, node.lo + 3, std::numeric_limits<double>::infinity());
    std::fill(node.hi, node.hi + 3, -std::numeric_limits<double>::infinity());
    auto grow = [&node](const double* l, const double* h) {
      for (int d = 0; d < 3; ++d) node.lo[d] = std::min(node.lo[d], l[d]);
      for (int d = 0; d < 3; ++d) node.hi[d] = std::max(node.hi[d], h[d]);
    };
    if (TriangleBvh::is_leaf(node)) {
      for (int32_t i = node.first; i < node.first + node.count; ++i)
        grow(&lo[3 * size_t(bvh.order[size_t(i)])], &hi[3 * size_t(bvh.order[size_t(i)])]);
    } else {
      for (int c = 0; c < 2; ++c)
        grow(bvh.nodes[size_t(node.first + c)].lo, bvh.nodes[size_t(node.first + c)].hi);
    }
  }
  return bvh;
}

// An icosphere of `level` with every coordinate moved by up to `amount`.
SurfaceMesh perturbed_sphere(int level, unsigned seed, double amount) {
  SurfaceMesh m = testing::icosphere(level);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  for (double& x : m.points) x += u(rng);
  return m;
}

TEST(TriangleBvh, TheTreeOfItsDefinitionOnAnyThreadCount) {
  // A perturbed sphere of 20,480 triangles (the top splits run before the
  // subtrees go to the threads), with repeated centres along x (ties).
  SurfaceMesh m = perturbed_sphere(5, 3, 0.01);
  for (size_t v = 0; v < m.num_vertices(); v += 7) m.points[3 * v] = 0.25;
  for (int leaf : {1, 4, 8}) {
    const TriangleBvh want = reference_bvh(m, leaf);
    for (int threads : {1, 2, 3}) {
      set_thread_count(threads);
      const TriangleBvh got = build_triangle_bvh(m, leaf);
      set_thread_count(0);
      ASSERT_EQ(got.order, want.order) << "leaf " << leaf << ", " << threads << " threads";
      ASSERT_EQ(got.nodes.size(), want.nodes.size());
      for (size_t n = 0; n < want.nodes.size(); ++n) {
        ASSERT_EQ(got.nodes[n].first, want.nodes[n].first) << "node " << n;
        ASSERT_EQ(got.nodes[n].count, want.nodes[n].count) << "node " << n;
        for (int d = 0; d < 3; ++d) {
          ASSERT_EQ(got.nodes[n].lo[d], want.nodes[n].lo[d]);
          ASSERT_EQ(got.nodes[n].hi[d], want.nodes[n].hi[d]);
        }
      }
    }
  }
}

// The self-traversal's calls (i, j) in order, as one stack-based loop
// makes them: (n, n) splits into its children's pair, then each child with
// itself (the second child first); (a, b) with overlapping boxes splits the
// node with the larger box (longest side; a on ties), its second child
// first.
std::vector<std::pair<int32_t, int32_t>> reference_leaf_pairs(const TriangleBvh& bvh) {
  std::vector<std::pair<int32_t, int32_t>> calls;
  std::vector<std::pair<int32_t, int32_t>> stack = {{0, 0}};
  auto extent = [](const TriangleBvh::Node& n) {
    return std::max({n.hi[0] - n.lo[0], n.hi[1] - n.lo[1], n.hi[2] - n.lo[2]});
  };
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    const TriangleBvh::Node &A = bvh.nodes[size_t(a)], &B = bvh.nodes[size_t(b)];
    const bool la = TriangleBvh::is_leaf(A), lb = TriangleBvh::is_leaf(B);
    if (a == b) {
      if (la) {
        for (int32_t i = A.first; i < A.first + A.count; ++i)
          for (int32_t j = i + 1; j < A.first + A.count; ++j) calls.emplace_back(i, j);
      } else {
        stack.insert(stack.end(),
                     {{A.first, A.first}, {A.first + 1, A.first + 1}, {A.first, A.first + 1}});
      }
      continue;
    }
    if (!boxes_overlap(A.lo, A.hi, B.lo, B.hi)) continue;
    if (la && lb) {
      for (int32_t i = A.first; i < A.first + A.count; ++i)
        for (int32_t j = B.first; j < B.first + B.count; ++j) calls.emplace_back(i, j);
    } else if (lb || (!la && extent(A) >= extent(B))) {
      stack.insert(stack.end(), {{A.first, b}, {A.first + 1, b}});
    } else {
      stack.insert(stack.end(), {{a, B.first}, {a, B.first + 1}});
    }
  }
  return calls;
}

TEST(TriangleBvh, LeafPairJobsMakeTheTraversalsCallsInOrder) {
  // Jobs run one after the other make the calls of one traversal in its
  // order, for any number of jobs asked (the threads merge per-job results
  // in job order: the first self-intersections found stay the same).
  const SurfaceMesh m = perturbed_sphere(4, 5, 0.02);
  for (int leaf : {1, 8}) {
    const TriangleBvh bvh = build_triangle_bvh(m, leaf);
    const auto want = reference_leaf_pairs(bvh);
    ASSERT_GT(want.size(), m.num_triangles());
    std::vector<std::pair<int32_t, int32_t>> whole;
    for_each_leaf_pair(bvh, [&](int32_t i, int32_t j) { whole.emplace_back(i, j); });
    EXPECT_EQ(whole, want) << "leaf " << leaf;
    for (size_t asked : {size_t(1), size_t(7), size_t(256), size_t(1) << 20}) {
      const std::vector<LeafPairJob> jobs = leaf_pair_jobs(bvh, asked);
      if (asked <= 256) {
        EXPECT_GE(jobs.size(), asked);
      }
      std::vector<std::pair<int32_t, int32_t>> got;
      for (const LeafPairJob& job : jobs)
        for_each_leaf_pair(bvh, job, [&](int32_t i, int32_t j) { got.emplace_back(i, j); });
      EXPECT_EQ(got, want) << "leaf " << leaf << ", " << asked << " jobs asked";
    }
  }
  EXPECT_TRUE(leaf_pair_jobs(TriangleBvh{}, 8).empty());
}

TEST(TriangleBvh, SmallAndEmptyMeshes) {
  SurfaceMesh one;
  one.points = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  one.triangles = {0, 1, 2};
  const TriangleBvh b = build_triangle_bvh(one);
  ASSERT_EQ(b.nodes.size(), 1u);
  EXPECT_TRUE(TriangleBvh::is_leaf(b.nodes[0]));
  EXPECT_EQ(b.order, std::vector<int32_t>{0});
  EXPECT_EQ(b.nodes[0].hi[0], 1.0);
  EXPECT_TRUE(build_triangle_bvh(SurfaceMesh{}).empty());
}

}  // namespace
}  // namespace vm
