#include "core/mesh/weld.h"

#include <gtest/gtest.h>

#include "core/io/stl.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

TriangleSoup soup_of(const SurfaceMesh& m) {
  auto r = read_stl(write_stl_binary(m));
  EXPECT_TRUE(r.ok());
  return r.value();
}

TEST(Weld, RecoversSharedVerticesOfATube) {
  SurfaceMesh tube = testing::open_tube(16, 6);
  WeldStats stats;
  SurfaceMesh w = weld(soup_of(tube), {}, &stats);
  EXPECT_EQ(w.num_vertices(), tube.num_vertices());
  EXPECT_EQ(w.num_triangles(), tube.num_triangles());
  EXPECT_EQ(stats.corners, 3 * tube.num_triangles());
  // Same connectivity up to renumbering: each welded triangle's corners are
  // at the positions of the original's.
  for (size_t t = 0; t < w.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c)
        EXPECT_FLOAT_EQ(float(w.points[3 * w.triangles[3 * t + k] + c]),
                        float(tube.points[3 * tube.triangles[3 * t + k] + c]));
}

TEST(Weld, MergesNearCoincidentCornersWithinTolerance) {
  TriangleSoup soup;
  // Two triangles sharing an edge, the second's copy of that edge moved by
  // 1e-9 (far below 1e-7 of the diagonal ~1.4).
  soup.coords = {0, 0,     0, 1, 0, 0, 0,     1, 0,  //
                 1, 1e-9f, 0, 1, 1, 0, 1e-9f, 1, 0};
  WeldStats stats;
  SurfaceMesh w = weld(soup, {}, &stats);
  EXPECT_EQ(w.num_vertices(), 4u);
  EXPECT_EQ(stats.merged_by_tolerance, 2u);
  EXPECT_EQ(w.triangles[1], w.triangles[3]);
  EXPECT_EQ(w.triangles[2], w.triangles[5]);

  WeldOptions exact;
  exact.relative_tolerance = 0;
  EXPECT_EQ(weld(soup, exact).num_vertices(), 6u);
}

TEST(Weld, AFarStrayTriangleDoesNotCollapseTheSurface) {
  // A tube of edges about 0.4 and one triangle a million units away: the
  // bounding box grows a million-fold, the tolerance must not.
  SurfaceMesh tube = testing::open_tube(16, 6);
  const size_t n = tube.num_vertices();
  SurfaceMesh with_stray = tube;
  with_stray.points.insert(with_stray.points.end(), {1e6, 0, 0, 1e6 + 1, 0, 0, 1e6, 1, 0});
  with_stray.triangles.insert(with_stray.triangles.end(),
                              {int32_t(n), int32_t(n + 1), int32_t(n + 2)});
  WeldStats stats;
  SurfaceMesh w = weld(soup_of(with_stray), {}, &stats);
  EXPECT_EQ(w.num_vertices(), n + 3);
  EXPECT_EQ(stats.merged_by_tolerance, 0u);
}

TEST(Weld, KeepsDistinctPointsApart) {
  TriangleSoup soup;
  soup.coords = {0, 0, 0, 1e-3f, 0, 0, 0, 1e-3f, 0};
  EXPECT_EQ(weld(soup).num_vertices(), 3u);
}

TEST(Weld, NegativeZeroIsZero) {
  TriangleSoup soup;
  soup.coords = {0, 0, 0, 1, 0, 0, 0, 1, 0, -0.0f, -0.0f, 0, 0, 1, 0, -1, 0, 0};
  WeldOptions exact;
  exact.relative_tolerance = 0;
  EXPECT_EQ(weld(soup, exact).num_vertices(), 4u);
}

TEST(Weld, FarFromTheOriginStillWelds) {
  // A unit tube translated by 1e20: cell coordinates exceed the int64 range.
  SurfaceMesh tube = testing::open_tube(12, 4);
  for (size_t i = 0; i < tube.points.size(); i += 3) tube.points[i] += 1e20;
  WeldStats stats;
  SurfaceMesh w = weld(soup_of(tube), {}, &stats);
  // In float, x collapses to 1e20 for all points: y and z still separate
  // the 12 x 5 grid positions into 12 angles x 5 heights at most.
  EXPECT_LE(w.num_vertices(), tube.num_vertices());
  EXPECT_GT(w.num_vertices(), 0u);
  EXPECT_EQ(w.num_triangles(), tube.num_triangles());
}

}  // namespace
}  // namespace vm

namespace vm {
namespace {

TEST(Weld, ADenseClusterAmongCoarseTrianglesMergesExactlyThePairsWithinTolerance) {
  // 3,000 coarse triangles (edges ~1: cells of a tenth of an edge; the
  // tolerance is 1e-7 of the diagonal, 1.3e-5) and 2,000 small ones packed
  // into a box 0.004 x 0.004 x 0.125: their 6,000 corners crowd a few cells,
  // so the cells shrink. There every 10th triangle's first corner has a
  // twin 5e-6 away (merged); the other corners are 2e-4 or more apart.
  TriangleSoup soup;
  auto add = [&](float x, float y, float z) { soup.coords.insert(soup.coords.end(), {x, y, z}); };
  for (int t = 0; t < 3000; ++t) {
    const float x = float(t % 60), y = float(t / 60);
    add(x, y, 100);
    add(x + 1, y, 100);
    add(x, y + 1, 100);
  }
  size_t twins = 0;
  for (int t = 0; t < 2000; ++t) {
    const float x = 0.001f * float(t % 4), y = 0.001f * float(t / 4 % 4),
                z = 0.001f * float(t / 16);
    add(x, y, z);
    add(x + 0.0002f, y + 0.0005f, z);
    if (t % 10 == 0) {
      add(x + 0.000005f, y, z);
      ++twins;
    } else {
      add(x + 0.0005f, y + 0.0002f, z + 0.0003f);
    }
  }
  WeldStats stats;
  const SurfaceMesh w = weld(soup, {}, &stats);
  EXPECT_EQ(stats.merged_by_tolerance, twins);
  EXPECT_EQ(w.num_triangles(), 5000u);
  EXPECT_EQ(w.num_vertices(), stats.exact_unique - twins);
}

TEST(WeldIndexed, SameAsTheSoupWeldForFloatCoordinates) {
  SurfaceMesh tube = testing::open_tube(16, 6);
  for (double& x : tube.points) x = double(float(x));
  WeldStats soup_stats, stats;
  SurfaceMesh a = weld(soup_of(tube), {}, &soup_stats);
  SurfaceMesh b = weld(tube.points, tube.triangles, {}, &stats);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(stats.corners, soup_stats.corners);
  EXPECT_EQ(stats.exact_unique, soup_stats.exact_unique);
}

TEST(WeldIndexed, MergesDuplicatesDropsUnusedKeepsOrder) {
  // Point 1 unused; point 4 duplicates point 0 bit for bit (with -0); point
  // 5 is point 2 moved by 1e-12 (within 1e-7 of the diagonal).
  std::vector<double> pts = {0, 0,    0, 9, 9,         9, 1, 0, 0, 0, 1,
                             0, -0.0, 0, 0, 1 + 1e-12, 0, 0, 0, 0, 1};
  std::vector<int32_t> tri = {3, 0, 2, 4, 5, 6};
  WeldStats stats;
  SurfaceMesh m = weld(pts, tri, {}, &stats);
  // First use: 3 -> 0, 0 -> 1, 2 -> 2, 6 -> 3.
  EXPECT_EQ(m.points, (std::vector<double>{0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}));
  EXPECT_EQ(m.triangles, (std::vector<int32_t>{0, 1, 2, 1, 2, 3}));
  EXPECT_EQ(stats.corners, 6u);
  EXPECT_EQ(stats.exact_unique, 5u);
  EXPECT_EQ(stats.merged_by_tolerance, 1u);
  // Doubles keep their precision: 1e-12 apart stays apart without tolerance.
  WeldOptions exact;
  exact.relative_tolerance = 0;
  EXPECT_EQ(weld(pts, tri, exact).num_vertices(), 5u);
}

}  // namespace
}  // namespace vm
