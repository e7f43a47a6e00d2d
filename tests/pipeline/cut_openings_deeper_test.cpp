// Cutting an opening again deeper into its vessel (prepare_surface.h's
// cut_openings_deeper): what the job does when the boundary layer meets an
// opening's plane at a grazing angle.
#include <gtest/gtest.h>

#include <cmath>

#include "core/io/stl.h"
#include "core/pipeline/prepare_surface.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

TEST(CutOpeningsDeeper, MovesTheOpeningInAlongItsVesselAndSaysSo) {
  // A tube of radius 1 along z from 0 to 8: openings at z = 0 and z = 8.
  auto r = prepare_surface(write_stl_binary(testing::open_tube(48, 40, 1.0, 8.0)));
  ASSERT_TRUE(r.ok()) << r.message();
  PreparedSurface s = std::move(r).value();
  ASSERT_EQ(s.topology.openings.size(), 2u);
  const size_t warnings = s.warnings.size();
  // A place on the rim at z = 8.
  ASSERT_TRUE(cut_openings_deeper(s, {Vec3{1, 0, 8}}, 0.5).ok());
  ASSERT_EQ(s.topology.openings.size(), 2u);
  ASSERT_EQ(s.opening_sources.size(), 2u);
  double top = -1, bottom = 1e9;
  for (size_t o = 0; o < 2; ++o) {
    const Opening& op = s.topology.openings[o];
    EXPECT_NEAR(op.radius, 1.0, 0.02);
    if (op.centroid[2] > 4) {
      top = op.centroid[2];
      EXPECT_EQ(s.opening_sources[o].kind, OpeningSource::kClip);
      for (int32_t v : op.loop) EXPECT_NEAR(s.mesh.points[3 * size_t(v) + 2], top, 1e-9);
    } else {
      bottom = op.centroid[2];
      EXPECT_EQ(s.opening_sources[o].kind, OpeningSource::kFile);
    }
  }
  EXPECT_NEAR(top, 7.5, 0.01) << "half a radius in";
  EXPECT_NEAR(bottom, 0, 1e-9) << "the other opening is kept";
  ASSERT_EQ(s.warnings.size(), warnings + 1);
  EXPECT_NE(s.warnings.back().find("was cut again 0.5 radii deeper"), std::string::npos)
      << s.warnings.back();
  EXPECT_TRUE(check_meshable(s).ok());
}

}  // namespace
}  // namespace vm
