#include "core/surface/relax_wall.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/mesh/self_intersection.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

TEST(RelaxWall, TakesOutANeedleAndLeavesTheRestOfTheWall) {
  // A tube of radius 1 whose vertex at angle 0, z = 4 is pulled in to 0.2
  // from the axis: a needle into the lumen.
  SurfaceMesh wall = testing::open_tube(48, 40, 1.0, 8.0);
  size_t needle = 0;
  for (size_t v = 0; v < wall.num_vertices(); ++v) {
    const Vec3 p = at(wall.points, int32_t(v));
    if (std::abs(p[2] - 4) < 1e-9 && std::abs(p[1]) < 1e-9 && p[0] > 0) needle = v;
  }
  const Vec3 tip = at(wall.points, int32_t(needle));
  ASSERT_NEAR(tip[0], 1, 1e-9);
  put(wall.points, int32_t(needle), Vec3{0.2, 0, 4});
  const SurfaceMesh before = wall;
  const double reach = 1.0;
  const WallRelaxation r = relax_wall_near(wall, {Vec3{0.2, 0, 4}}, reach);
  ASSERT_TRUE(r.applied);
  EXPECT_GT(r.vertices, 1u);
  const Vec3 p = at(wall.points, int32_t(needle));
  EXPECT_GT(std::hypot(p[0], p[1]), 0.6) << "the needle is mostly gone";
  EXPECT_EQ(find_self_intersections(wall).pairs, 0u);
  for (size_t v = 0; v < wall.num_vertices(); ++v) {
    const Vec3 q = at(before.points, int32_t(v));
    const bool far = norm(q - Vec3{0.2, 0, 4}) >= reach;
    const bool rim = q[2] < 1e-9 || q[2] > 8 - 1e-9;
    if (far || rim) {
      EXPECT_EQ(at(wall.points, int32_t(v)), q) << v;
    }
  }
  // Nothing near: nothing done.
  const SurfaceMesh now = wall;
  EXPECT_FALSE(relax_wall_near(wall, {Vec3{9, 9, 9}}, reach).applied);
  EXPECT_EQ(wall.points, now.points);
}

}  // namespace
}  // namespace vm
