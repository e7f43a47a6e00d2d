#include "core/layers/slide_wall_points.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/mesh/volume_check.h"
#include "core/quality/triangle_quality.h"

namespace vm {
namespace {

// Wall z = 0 of a cone of tetrahedra below it: edge a (0) - b (1) split at
// its midpoint m (4) between apexes c (2) and d (3), the wall triangles
// (a, m, c), (m, b, c), (b, m, d), (m, a, d) tagged 0 (counterclockwise seen
// from +z, out of the cone), apex e (5) below, the cone's sides tagged 1.
VolumeMesh split_pair(double cx, double dx) {
  VolumeMesh m;
  m.points = {0, 0, 0, 2, 0, 0, cx, 1, 0, dx, -1, 0, 1, 0, 0, 1, 0, -1.5};
  m.triangles = {0, 4, 2, 4, 1, 2, 1, 4, 3, 4, 0, 3};
  m.triangle_tag.assign(4, 0);
  for (size_t t = 0; t < 4; ++t)
    m.tets.insert(m.tets.end(),
                  {m.triangles[3 * t], m.triangles[3 * t + 2], m.triangles[3 * t + 1], 5});
  m.tet_region.assign(4, 0);
  m.triangles.insert(m.triangles.end(), {2, 5, 0, 1, 5, 2, 3, 5, 1, 0, 5, 3});
  m.triangle_tag.resize(8, 1);
  return m;
}

double wall_min(const VolumeMesh& m) {
  double q = 1;
  for (size_t t = 0; t < 4; ++t) {
    const int32_t* v = &m.triangles[3 * t];
    q = std::min(q, triangle_gamma(&m.points[3 * size_t(v[0])], &m.points[3 * size_t(v[1])],
                                   &m.points[3 * size_t(v[2])]));
  }
  return q;
}

TEST(SlideWallPoints, PointSlidesAlongItsEdgeToBetterTheWall) {
  VolumeMesh m = split_pair(0.2, 0.3);  // both apexes near a: m is better nearer a
  ASSERT_TRUE(check_volume_mesh(m).ok()) << check_volume_mesh(m).message();
  const double before = wall_min(m);
  const SlideStats s = slide_wall_points(m, {WallPointColumn{{4, 0, 1}}}, 0);
  EXPECT_EQ(s.moved, 1u);
  EXPECT_GT(wall_min(m), before + 0.01);
  EXPECT_DOUBLE_EQ(s.wall_min, before);
  EXPECT_DOUBLE_EQ(s.wall_min_after, wall_min(m));
  // Still on the edge, inside it, the mesh still valid.
  EXPECT_EQ(m.points[13], 0.0);
  EXPECT_EQ(m.points[14], 0.0);
  EXPECT_GT(m.points[12], 0.0);
  EXPECT_LT(m.points[12], 1.0);
  const auto check = check_volume_mesh(m);
  EXPECT_TRUE(check.ok()) << check.message();
}

TEST(SlideWallPoints, SymmetricSplitStays) {
  VolumeMesh m = split_pair(1, 1);  // the midpoint is best
  const std::vector<double> points = m.points;
  const SlideStats s = slide_wall_points(m, {WallPointColumn{{4, 0, 1}}}, 0);
  EXPECT_EQ(s.moved, 0u);
  EXPECT_EQ(m.points, points);
}

TEST(SlideWallPoints, ColumnMovesTogetherOrNotAtAll) {
  // The apex as the column's second point, on the segment from c to d: it
  // would move with m by the same t, onto the wall, flattening the cone's
  // tetrahedra, so nothing moves.
  VolumeMesh m = split_pair(0.2, 0.3);
  const std::vector<double> points = m.points;
  const SlideStats s = slide_wall_points(m, {WallPointColumn{{4, 0, 1, 5, 2, 3}}}, 0);
  EXPECT_EQ(s.moved, 0u);
  EXPECT_EQ(m.points, points);
}

}  // namespace
}  // namespace vm
