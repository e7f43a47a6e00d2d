#include "core/mesh/self_crossings.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/phantom/vessel_phantom.h"
#include "tests/support/phantoms.h"
#include "tests/support/pushed_tube.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

TEST(SelfCrossings, ADentPushedThroughTheOppositeWallIsOnePlaceWhereItCrosses) {
  const SurfaceMesh tube = testing::pushed_tube();
  const SelfCrossings c = find_self_crossings(tube);
  EXPECT_GT(c.pairs, 0u);
  ASSERT_EQ(c.place_count, 1u);
  ASSERT_EQ(c.places.size(), 1u);
  // The dent (around y = 0, z = 4) passes the opposite wall (x = -1).
  const Vec3& p = c.places[0];
  EXPECT_NEAR(p[0], -1, 0.1) << point_text(p);
  EXPECT_LT(std::abs(p[1]), 0.6) << point_text(p);
  EXPECT_LT(std::abs(p[2] - 4), 0.6) << point_text(p);
}

TEST(SelfCrossings, TwoDentsAreTwoPlacesAndAtMostTheAskedAreKept) {
  SurfaceMesh tube = testing::pushed_tube();
  // A second dent at z = 1.5, from the other side (x = -1, towards +x).
  testing::push_dent(tube, 1.5, -2.6);
  const SelfCrossings c = find_self_crossings(tube);
  EXPECT_EQ(c.place_count, 2u);
  ASSERT_EQ(c.places.size(), 2u);
  bool near_4 = false, near_15 = false;
  for (const Vec3& p : c.places) {
    near_4 |= std::abs(p[2] - 4) < 0.6 && std::abs(p[0] + 1) < 0.1;
    near_15 |= std::abs(p[2] - 1.5) < 0.6 && std::abs(p[0] - 1) < 0.1;
  }
  EXPECT_TRUE(near_4 && near_15);
  const SelfCrossings one = find_self_crossings(tube, 1);
  EXPECT_EQ(one.place_count, 2u);
  EXPECT_EQ(one.places.size(), 1u);
  EXPECT_EQ(one.pairs, c.pairs);
}

TEST(SelfCrossings, CleanSurfacesHaveNone) {
  for (const SurfaceMesh& m : {testing::open_tube(48, 40, 1.0, 8.0),
                               testing::phantom(PhantomKind::kBifurcation, true, 0.1, 0.3)}) {
    const SelfCrossings c = find_self_crossings(m);
    EXPECT_EQ(c.pairs, 0u);
    EXPECT_EQ(c.place_count, 0u);
    EXPECT_TRUE(c.places.empty());
  }
}

}  // namespace
}  // namespace vm
