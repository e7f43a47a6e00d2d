#include "core/mesh/level_loops.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/mesh/adjacency.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

std::vector<double> coordinate(const SurfaceMesh& m, int k) {
  std::vector<double> f(m.num_vertices());
  for (size_t v = 0; v < f.size(); ++v) f[v] = m.points[3 * v + size_t(k)];
  return f;
}

TEST(LevelLoops, ASectionOfAClosedTubeIsOneLoopAroundIt) {
  const SurfaceMesh tube = testing::capped_tube(24, 8, 1.0, 4.0);
  const TriangleAdjacency adj = build_adjacency(tube);
  const std::vector<LevelLoop> loops = level_loops(tube, adj, coordinate(tube, 2), 2.1);
  ASSERT_EQ(loops.size(), 1u);
  const LevelLoop& l = loops[0];
  EXPECT_TRUE(l.closed);
  EXPECT_EQ(l.triangles.size(), l.size());
  // Two crossed edges per band square (vertical and diagonal).
  EXPECT_EQ(l.size(), 48u);
  for (size_t i = 0; i < l.size(); ++i) {
    EXPECT_NEAR(l.points[3 * i + 2], 2.1, 1e-12);
    EXPECT_LE(tube.points[3 * size_t(l.edges[i][0]) + 2], 2.1);
    EXPECT_GT(tube.points[3 * size_t(l.edges[i][1]) + 2], 2.1);
  }
  const CurveShape s = curve_shape(l.points);
  EXPECT_NEAR(s.radius, std::sqrt(12 * std::sin(2 * std::numbers::pi / 24) / std::numbers::pi),
              1e-9);
  EXPECT_NEAR(s.centroid[2], 2.1, 1e-12);
  // "Above" (z > 2.1) on the left seen from outside: counterclockwise
  // seen from +z.
  EXPECT_GT(s.vector_area[2], 0);
  EXPECT_NEAR(s.max_distance, 1.0, 1e-9);
  EXPECT_NE(winding_number(l.points, {0, 0, 2.1}, {0, 0, 1}), 0);
  EXPECT_EQ(winding_number(l.points, {3, 0, 2.1}, {0, 0, 1}), 0);
  EXPECT_NEAR(distance_to_polygon(l.points, {3, 0, 2.1}), 2.0, 1e-9);
}

TEST(LevelLoops, AVertexAtTheValueIsAPointOfTheCurve) {
  const SurfaceMesh tube = testing::capped_tube(16, 8, 1.0, 4.0);
  const TriangleAdjacency adj = build_adjacency(tube);
  // Ring 4 lies at z = 2: its vertices count as below and are the points.
  const std::vector<LevelLoop> loops = level_loops(tube, adj, coordinate(tube, 2), 2.0);
  ASSERT_EQ(loops.size(), 1u);
  for (size_t i = 0; i < loops[0].size(); ++i) {
    EXPECT_EQ(loops[0].points[3 * i + 2], 2.0);
    EXPECT_EQ(tube.points[3 * size_t(loops[0].edges[i][0]) + 2], 2.0);
  }
}

TEST(LevelLoops, CurvesEndAtOpeningsAndAtTheSubsetsEdge) {
  const SurfaceMesh tube = testing::open_tube(16, 8, 1.0, 4.0);
  const TriangleAdjacency adj = build_adjacency(tube);
  // The plane x = 0.1 cuts the tube along its length: two open curves.
  const std::vector<LevelLoop> lengthwise = level_loops(tube, adj, coordinate(tube, 0), 0.1);
  ASSERT_EQ(lengthwise.size(), 2u);
  for (const LevelLoop& l : lengthwise) {
    EXPECT_FALSE(l.closed);
    EXPECT_EQ(l.size(), l.triangles.size() + 1);
  }
  // Only the triangles of the lower half: the ring at z = 3 is not found,
  // the ring at z = 1.1 is.
  std::vector<int32_t> lower;
  for (size_t t = 0; t < tube.num_triangles() / 2; ++t) lower.push_back(int32_t(t));
  const std::vector<double> z = coordinate(tube, 2);
  EXPECT_TRUE(level_loops(tube, adj, z, 3.1, lower).empty());
  const std::vector<LevelLoop> low = level_loops(tube, adj, z, 1.1, lower);
  ASSERT_EQ(low.size(), 1u);
  EXPECT_TRUE(low[0].closed);
}

}  // namespace
}  // namespace vm
