#include "core/mesh/self_intersection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <random>

#include "core/phantom/vessel_phantom.h"
#include "core/util/parallel.h"
#include "tests/support/icosphere.h"
#include "tests/support/phantoms.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

// Two triangles (given as 18 coordinates) in one mesh, no shared index.
SurfaceMesh pair(const std::vector<double>& coords) {
  SurfaceMesh m;
  m.points = coords;
  m.triangles = {0, 1, 2, 3, 4, 5};
  return m;
}

// Appends `b` to `a` (indices shifted).
SurfaceMesh merged(SurfaceMesh a, const SurfaceMesh& b) {
  const int32_t off = int32_t(a.num_vertices());
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  for (int32_t v : b.triangles) a.triangles.push_back(v + off);
  return a;
}

SurfaceMesh translated(SurfaceMesh m, double x, double y, double z) {
  for (size_t i = 0; i < m.points.size(); i += 3)
    m.points[i] += x, m.points[i + 1] += y, m.points[i + 2] += z;
  return m;
}

TEST(SelfIntersection, CrossingTouchingAndSeparateTriangles) {
  // A horizontal triangle pierced by a vertical one.
  EXPECT_TRUE(triangles_intersect(pair({0, 0, 0, 2, 0, 0, 0, 2, 0,  //
                                        0.5, 0.5, -1, 0.5, 0.5, 1, 1.5, 1.5, 0.5}),
                                  0, 1));
  // Parallel, separate.
  EXPECT_FALSE(triangles_intersect(pair({0, 0, 0, 2, 0, 0, 0, 2, 0,  //
                                         0, 0, 1e-12, 2, 0, 1e-12, 0, 2, 1e-12}),
                                   0, 1));
  // A vertex of the second exactly on the first's interior (touching).
  EXPECT_TRUE(triangles_intersect(pair({0, 0, 0, 2, 0, 0, 0, 2, 0,  //
                                        0.5, 0.5, 0, 0.5, 0.5, 1, 1, 0.2, 1}),
                                  0, 1));
  // Just above it: separate (exactness: 1e-300 is not rounded away).
  EXPECT_FALSE(triangles_intersect(pair({0, 0, 0, 2, 0, 0, 0, 2, 0,  //
                                         0.5, 0.5, 1e-300, 0.5, 0.5, 1, 1, 0.2, 1}),
                                   0, 1));
  // Edge through edge (the vertical triangle's edge crosses the
  // horizontal one's hypotenuse).
  EXPECT_TRUE(triangles_intersect(pair({0, 0, 0, 2, 0, 0, 0, 2, 0,  //
                                        1, 1, -1, 1, 1, 1, 3, 3, 0}),
                                  0, 1));
  // Coplanar overlapping, coplanar disjoint, coplanar nested.
  EXPECT_TRUE(triangles_intersect(pair({0, 0, 0, 2, 0, 0, 0, 2, 0,  //
                                        1, 1, 0, -1, 0.5, 0, 1, -1, 0}),
                                  0, 1));
  EXPECT_FALSE(triangles_intersect(pair({0, 0, 0, 2, 0, 0, 0, 2, 0,  //
                                         1.1, 1.1, 0, 3, 1, 0, 1, 3, 0}),
                                   0, 1));
  EXPECT_TRUE(triangles_intersect(pair({0, 0, 0, 4, 0, 0, 0, 4, 0,  //
                                        0.5, 0.5, 0, 1, 0.5, 0, 0.5, 1, 0}),
                                  0, 1));
}

TEST(SelfIntersection, SharedVertexAndSharedEdge) {
  SurfaceMesh m;
  // Triangle 0 horizontal; triangle 1 shares vertex 0 and dives through it;
  // triangle 2 shares vertex 0 and stays above; triangle 3 shares edge 0-1
  // and rises; triangle 4 shares edge 0-1 and folds onto triangle 0.
  m.points = {0,   0,   0,  2,   0,   0, 0, 2, 0,  // 0 1 2
              0.5, 0.5, -1, 0.5, 0.5, 1,           // 3 4
              1,   1,   1,  0.2, 1,   1,           // 5 6
              1,   -1,  1,                         // 7
              0.5, 0.5, 0};                        // 8
  m.triangles = {0, 1, 2, 0, 3, 4, 0, 5, 6, 1, 0, 7, 0, 1, 8};
  EXPECT_TRUE(triangles_intersect(m, 0, 1));
  EXPECT_FALSE(triangles_intersect(m, 0, 2));
  EXPECT_FALSE(triangles_intersect(m, 0, 3));
  EXPECT_TRUE(triangles_intersect(m, 0, 4));
  // Coplanar neighbors across an edge (a flat fan) do not intersect.
  SurfaceMesh flat;
  flat.points = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, -1, -1, 0};
  flat.triangles = {0, 1, 2, 2, 1, 3, 0, 2, 4, 4, 1, 0};
  const SelfIntersectionReport r = find_self_intersections(flat);
  EXPECT_EQ(r.pairs, 0u);
  // Sharing a vertex in the plane, sectors overlapping.
  SurfaceMesh fan;
  fan.points = {0, 0, 0, 2, 0, 0, 0, 2, 0, 2, 1, 0, 1, 2, 0};
  fan.triangles = {0, 1, 2, 0, 3, 4};
  EXPECT_TRUE(triangles_intersect(fan, 0, 1));
  // The same triangle twice (either orientation).
  SurfaceMesh dup;
  dup.points = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  dup.triangles = {0, 1, 2, 0, 2, 1};
  EXPECT_EQ(find_self_intersections(dup).pairs, 1u);
  // Degenerate triangles are counted and skipped.
  SurfaceMesh degenerate;
  degenerate.points = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0};
  degenerate.triangles = {0, 1, 2, 0, 1, 3};
  const SelfIntersectionReport d = find_self_intersections(degenerate);
  EXPECT_EQ(d.degenerate_triangles, 1u);
  EXPECT_EQ(d.pairs, 0u);
}

void expect_clean(const SurfaceMesh& m, const char* name) {
  const SelfIntersectionReport r = find_self_intersections(m);
  EXPECT_EQ(r.pairs, 0u) << name;
  EXPECT_EQ(r.degenerate_triangles, 0u) << name;
  EXPECT_TRUE(r.examples.empty()) << name;
  EXPECT_GT(r.tested_pairs, m.num_triangles()) << name;  // neighbors are tested
}

TEST(SelfIntersection, CleanSurfacesHaveNone) {
  expect_clean(testing::icosphere(5), "sphere");
  expect_clean(testing::torus(120, 40), "torus");
  expect_clean(testing::open_tube(48, 30), "open tube");
  expect_clean(testing::phantom(PhantomKind::kBifurcation, true, 0.1, 0.3), "bifurcation phantom");
  expect_clean(testing::phantom(PhantomKind::kTorus, false, 0.1, 0.3), "torus phantom");
  // Two spheres apart (closest gap 0.01).
  expect_clean(merged(testing::icosphere(3), testing::icosphere(3, 1.0, 2.01, 0, 0)),
               "two spheres");
}

TEST(SelfIntersection, FindsKnownCrossings) {
  // Two overlapping spheres cross along a circle.
  const SurfaceMesh a = testing::icosphere(4);
  const SurfaceMesh two = merged(a, translated(a, 1.0, 0.2, 0.1));
  const SelfIntersectionReport r = find_self_intersections(two, 5);
  EXPECT_GT(r.pairs, 50u);
  ASSERT_EQ(r.examples.size(), 5u);
  for (const auto& e : r.examples) {
    EXPECT_LT(e[0], e[1]);
    EXPECT_LT(size_t(e[0]), a.num_triangles());  // one triangle of each sphere
    EXPECT_GE(size_t(e[1]), a.num_triangles());
    EXPECT_TRUE(triangles_intersect(two, e[0], e[1]));
  }
  // A torus with one vertex pulled through the opposite side of the tube.
  SurfaceMesh t = testing::torus(40, 20, 3.0, 1.0);
  t.points[0] -= 2.5;  // vertex 0 at (4, 0, 0) moves to (1.5, 0, 0)
  const SelfIntersectionReport f = find_self_intersections(t);
  EXPECT_GT(f.pairs, 0u);
  for (const auto& e : f.examples) EXPECT_TRUE(triangles_intersect(t, e[0], e[1]));
}

// n random triangles (no shared vertices) of size about 0.5 in a box of 4.
SurfaceMesh triangle_soup(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  SurfaceMesh m;
  for (int t = 0; t < n; ++t) {
    const double c[3] = {4 * u(rng), 4 * u(rng), 4 * u(rng)};
    for (int k = 0; k < 3; ++k)
      m.points.insert(m.points.end(),
                      {c[0] + 0.5 * u(rng), c[1] + 0.5 * u(rng), c[2] + 0.5 * u(rng)});
    m.triangles.insert(m.triangles.end(), {3 * t, 3 * t + 1, 3 * t + 2});
  }
  return m;
}

TEST(SelfIntersection, MatchesAllPairsOnASmallMesh) {
  // Random triangles in a box: the hierarchy finds exactly the pairs the
  // quadratic loop finds.
  const SurfaceMesh m = triangle_soup(300, 11);
  size_t brute = 0;
  for (int32_t i = 0; i < 300; ++i)
    for (int32_t j = i + 1; j < 300; ++j) brute += triangles_intersect(m, i, j);
  EXPECT_GT(brute, 0u);
  EXPECT_EQ(find_self_intersections(m).pairs, brute);
}

TEST(SelfIntersection, FlaggedTrianglesGetExactlyTheirPairs) {
  // Random triangles: the pairs holding a flagged triangle, each once, as
  // the quadratic loop counts them; all flagged: every pair.
  const SurfaceMesh m = triangle_soup(300, 5);
  std::vector<uint8_t> flagged(300, 0);
  for (size_t t = 0; t < 300; t += 7) flagged[t] = 1;
  size_t brute = 0, all = 0;
  for (int32_t i = 0; i < 300; ++i)
    for (int32_t j = i + 1; j < 300; ++j) {
      const bool hit = triangles_intersect(m, i, j);
      all += hit;
      brute += hit && (flagged[size_t(i)] || flagged[size_t(j)]);
    }
  EXPECT_GT(brute, 0u);
  EXPECT_LT(brute, all);
  const SelfIntersectionReport r = find_self_intersections_of(m, flagged, 1000);
  EXPECT_EQ(r.pairs, brute);
  for (const auto& e : r.examples) {
    EXPECT_LT(e[0], e[1]);
    EXPECT_TRUE(flagged[size_t(e[0])] || flagged[size_t(e[1])]);
  }
  EXPECT_EQ(find_self_intersections_of(m, std::vector<uint8_t>(300, 1)).pairs, all);
  EXPECT_EQ(find_self_intersections_of(m, std::vector<uint8_t>(300, 0)).pairs, 0u);
  // On a clean surface with one vertex pulled through: only the triangles
  // around it need looking at.
  SurfaceMesh t = testing::torus(40, 20, 3.0, 1.0);
  t.points[0] -= 2.5;
  std::vector<uint8_t> around(t.num_triangles(), 0);
  for (size_t k = 0; k < t.num_triangles(); ++k)
    for (int c = 0; c < 3; ++c) around[k] |= t.triangles[3 * k + size_t(c)] == 0;
  EXPECT_EQ(find_self_intersections_of(t, around).pairs, find_self_intersections(t).pairs);
}

TEST(SelfIntersection, ChangedTrianglesAreThoseThatMoved) {
  const SurfaceMesh before = testing::torus(12, 8, 3.0, 1.0);
  // Renumbered (vertices reversed, triangles rotated and reordered): the
  // same surface, nothing changed.
  SurfaceMesh same;
  const int32_t nv = int32_t(before.num_vertices());
  for (int32_t v = nv - 1; v >= 0; --v)
    same.points.insert(same.points.end(), &before.points[3 * size_t(v)],
                       &before.points[3 * size_t(v)] + 3);
  for (size_t t = before.num_triangles(); t-- > 0;) {
    const int32_t* T = &before.triangles[3 * t];
    same.triangles.insert(same.triangles.end(), {nv - 1 - T[1], nv - 1 - T[2], nv - 1 - T[0]});
  }
  const std::vector<uint8_t> none = changed_triangles(before, same);
  EXPECT_EQ(std::count(none.begin(), none.end(), 1), 0);
  // One vertex moved: exactly its triangles.
  SurfaceMesh moved = before;
  moved.points[3 * 5 + 2] += 0.1;
  const std::vector<uint8_t> star = changed_triangles(before, moved);
  for (size_t t = 0; t < moved.num_triangles(); ++t) {
    const int32_t* T = &moved.triangles[3 * t];
    EXPECT_EQ(star[t], T[0] == 5 || T[1] == 5 || T[2] == 5) << t;
  }
}

TEST(SelfIntersection, SameReportOnAnyThreadCount) {
  // Two overlapping spheres: the count, the tested pairs and the first
  // examples (the order of a sequential search) on 1, 2 and 3 threads.
  const SurfaceMesh a = testing::icosphere(4);
  const SurfaceMesh two = merged(a, translated(a, 1.0, 0.2, 0.1));
  std::vector<uint8_t> flagged(two.num_triangles(), 0);
  for (size_t t = 0; t < flagged.size(); t += 3) flagged[t] = 1;
  auto same = [](const SelfIntersectionReport& x, const SelfIntersectionReport& y) {
    return x.pairs == y.pairs && x.tested_pairs == y.tested_pairs && x.examples == y.examples &&
           x.degenerate_triangles == y.degenerate_triangles;
  };
  set_thread_count(1);
  const SelfIntersectionReport all1 = find_self_intersections(two, 1000),
                               few1 = find_self_intersections(two, 7),
                               of1 = find_self_intersections_of(two, flagged, 1000);
  EXPECT_GT(all1.pairs, 50u);
  EXPECT_EQ(all1.examples.size(), std::min<size_t>(all1.pairs, 1000));
  EXPECT_TRUE(std::equal(few1.examples.begin(), few1.examples.end(), all1.examples.begin()));
  EXPECT_GT(of1.pairs, 0u);
  EXPECT_LT(of1.pairs, all1.pairs);
  for (int threads : {2, 3}) {
    set_thread_count(threads);
    EXPECT_TRUE(same(find_self_intersections(two, 1000), all1)) << threads << " threads";
    EXPECT_TRUE(same(find_self_intersections(two, 7), few1)) << threads << " threads";
    EXPECT_TRUE(same(find_self_intersections_of(two, flagged, 1000), of1)) << threads << " threads";
  }
  set_thread_count(0);
}

TEST(SelfIntersection, LargeCleanSurfaceTestsFewPairs) {
  // 200k triangles: none intersect, and the box hierarchy keeps the exact
  // tests to the neighbors (a few per triangle), not all pairs. Timing is
  // printed for information only (speed is measured in bench/).
  const SurfaceMesh m = testing::torus(500, 200, 3.0, 1.0);
  const auto t0 = std::chrono::steady_clock::now();
  const SelfIntersectionReport r = find_self_intersections(m);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.pairs, 0u);
  EXPECT_LT(r.tested_pairs, 20 * m.num_triangles());
  std::cout << "[ info ] self-intersection check of " << m.num_triangles() << " triangles: " << s
            << " s (" << r.tested_pairs << " pairs with overlapping boxes)\n";
}

}  // namespace
}  // namespace vm
