#include "core/param/fixed_boundary_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/param/param_test_meshes.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

using testing::disk;

class DiskMaps : public ::testing::TestWithParam<DiskWeights> {};

TEST_P(DiskMaps, ReproduceTheUnitDiskUpToRotation) {
  // A jittered planar unit disk whose boundary is a regular polygon: both
  // weights reproduce linear functions, so the map is a rotation.
  std::vector<std::complex<double>> planar;
  SurfaceMesh m = disk(
      10, 6, 0.3,
      [](double x, double y) {
        return std::array<double, 3>{x, y, 0.0};
      },
      &planar);
  auto r = map_to_disk(m, GetParam());
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().flipped_triangles, 0u);
  EXPECT_LT(testing::similarity_residual(planar, testing::as_complex(r.value().uv)), 1e-9);
  // Boundary on the unit circle.
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    if (std::abs(planar[v]) > 0.999) {
      EXPECT_NEAR(std::hypot(r.value().uv[2 * v], r.value().uv[2 * v + 1]), 1.0, 1e-12);
    }
  }
}

TEST_P(DiskMaps, SphericalCapIsEmbedded) {
  SurfaceMesh cap = disk(16, 6, 0.2, [](double x, double y) {
    double t = 1.3 * std::hypot(x, y), phi = std::atan2(y, x);
    return std::array<double, 3>{std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi),
                                 std::cos(t)};
  });
  auto r = map_to_disk(cap, GetParam());
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().flipped_triangles, 0u);
  EXPECT_NEAR(signed_area(cap, r.value().uv), std::numbers::pi, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Weights, DiskMaps,
                         ::testing::Values(DiskWeights::kHarmonic, DiskWeights::kMeanValue));

TEST(DiskMaps, MeanValueStaysOneToOneOnAStronglyJitteredPatch) {
  // Strongly jittered, curved disk with obtuse triangles: Floater's weights
  // are positive, so the map stays one-to-one whatever the shapes.
  SurfaceMesh m = disk(8, 5, 0.9, [](double x, double y) {
    return std::array<double, 3>{x, y, 0.3 * x * y};
  });
  auto r = map_to_disk(m, DiskWeights::kMeanValue);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().flipped_triangles, 0u);
}

TEST(DiskMaps, NeedExactlyOneBoundaryLoop) {
  auto r = map_to_disk(testing::open_tube(10, 4), DiskWeights::kMeanValue);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("exactly one boundary loop, found 2"), std::string::npos);
}

}  // namespace
}  // namespace vm
