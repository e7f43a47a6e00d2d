#include "core/mesh/chord_radius.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/phantom/vessel_phantom.h"
#include "core/surface/remesh_surface.h"
#include "tests/support/phantoms.h"
#include "tests/support/remesh_options.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

TEST(ChordRadius, ExactOnTubeAndTorus) {
  // Even vertex counts around: each ray of the tube meets the opposite
  // vertex; the torus's trapezoid quads tilt its normals slightly.
  const SurfaceMesh tube = testing::open_tube(32, 12, 1.5, 4.0);
  for (double r : chord_radius(tube)) EXPECT_NEAR(r, 1.5, 1e-9);
  const SurfaceMesh torus = testing::torus(48, 16, 3.0, 1.0);
  for (double r : chord_radius(torus)) EXPECT_NEAR(r, 1.0, 2e-3);
}

TEST(ChordRadius, RemeshedBifurcationNearTheOpenings) {
  PhantomTruth truth;
  auto remeshed =
      remesh_surface(testing::noisy_bifurcation(0.15, &truth), testing::uniform_remesh(0.15));
  ASSERT_TRUE(remeshed.ok()) << remeshed.message();
  const SurfaceMesh& wall = remeshed.value().mesh;
  const std::vector<double> radius = chord_radius(wall);
  ASSERT_EQ(radius.size(), wall.num_vertices());
  // Within one radius of each opening's center, R is the opening's radius
  // within 10% (median over those vertices).
  for (size_t o = 0; o < truth.opening_centers.size(); ++o) {
    std::vector<double> near;
    for (size_t v = 0; v < wall.num_vertices(); ++v) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k)
        d2 += std::pow(wall.points[3 * v + size_t(k)] - truth.opening_centers[o][size_t(k)], 2);
      if (d2 < std::pow(1.5 * truth.opening_radii[o], 2)) near.push_back(radius[v]);
    }
    ASSERT_GT(near.size(), 10u);
    EXPECT_NEAR(testing::median(near), truth.opening_radii[o], 0.1 * truth.opening_radii[o]);
  }
  // Every value is a measured length: nothing near the half diagonal.
  const double diag = bounding_box(wall.points).diagonal();
  for (double r : radius) EXPECT_LT(r, 0.25 * diag);
}

}  // namespace
}  // namespace vm
