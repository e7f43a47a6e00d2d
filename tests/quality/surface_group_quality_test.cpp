#include "core/quality/surface_group_quality.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vm {
namespace {

TEST(SurfaceGroupQuality, GroupsByTagWithTheRingsApart) {
  // Three triangles: an equilateral one (wall), a right isosceles one (cap
  // disc) and a flat one in the ring range (cap ring); tag 2 is unused.
  VolumeMesh m;
  m.points = {0, 0, 0, 1, 0, 0, 0.5, std::sqrt(3.0) / 2, 0, 0, 1, 0, 10, 0.1, 0};
  m.triangles = {0, 1, 2, 0, 1, 3, 0, 1, 4};
  m.triangle_tag = {0, 1, 1};
  const auto q = surface_group_quality(m, {"wall", "inlet", "unused"}, 2, 3);
  ASSERT_EQ(q.size(), 2u);
  EXPECT_EQ(q[0].name, "wall");
  EXPECT_EQ(q[0].quality.count, 1u);
  EXPECT_NEAR(q[0].quality.min, 1.0, 1e-6);
  EXPECT_EQ(q[0].ring.count, 0u);
  EXPECT_EQ(q[1].name, "inlet");
  EXPECT_EQ(q[1].tag, 1);
  EXPECT_EQ(q[1].quality.count, 1u);
  // Right isosceles: 2 r_in / r_circ = 2 (2 - sqrt 2) / 2 / (sqrt 2 / 2).
  EXPECT_NEAR(q[1].quality.min, 2 * (1 - std::sqrt(0.5)) / std::sqrt(0.5), 1e-6);
  EXPECT_EQ(q[1].ring.count, 1u);
  EXPECT_LT(q[1].ring.min, 0.05);
}

}  // namespace
}  // namespace vm
