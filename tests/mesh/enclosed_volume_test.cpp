#include "core/mesh/enclosed_volume.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/support/icosphere.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

constexpr double kPi = std::numbers::pi;

// Axis-aligned box [0, a] x [0, b] x [0, c] shifted by (x, y, z), outward.
SurfaceMesh box(double a, double b, double c, double x = 0, double y = 0, double z = 0) {
  SurfaceMesh m;
  for (int k = 0; k < 8; ++k)
    m.points.insert(m.points.end(),
                    {x + (k & 1 ? a : 0), y + (k & 2 ? b : 0), z + (k & 4 ? c : 0)});
  m.triangles = {0, 2, 3, 0, 3, 1,   // z = 0, facing -z
                 4, 5, 7, 4, 7, 6,   // z = c
                 0, 1, 5, 0, 5, 4,   // y = 0
                 2, 6, 7, 2, 7, 3,   // y = b
                 0, 4, 6, 0, 6, 2,   // x = 0
                 1, 3, 7, 1, 7, 5};  // x = a
  return m;
}

TEST(EnclosedVolume, BoxExactAndTranslationInvariant) {
  EXPECT_NEAR(enclosed_volume(box(1, 2, 3)), 6.0, 1e-14);
  EXPECT_NEAR(enclosed_volume(box(1, 2, 3, 1e6, -2e6, 3e5)), 6.0, 1e-6);
  EXPECT_NEAR(surface_area(box(1, 2, 3)), 2 * (2 + 3 + 6), 1e-14);
}

TEST(EnclosedVolume, InwardOrientationIsNegative) {
  SurfaceMesh m = box(2, 2, 2);
  for (size_t t = 0; t < m.num_triangles(); ++t) testing::flip_triangle(m, t);
  EXPECT_NEAR(enclosed_volume(m), -8.0, 1e-14);
}

TEST(EnclosedVolume, SphereAndTorusConvergeToTheirVolumes) {
  // Inscribed polyhedra: below the exact volume, error O(h^2).
  const double v_sphere = 4.0 / 3.0 * kPi * 8;  // r = 2
  double previous_error = 1e300;
  for (int level = 2; level <= 5; ++level) {
    const double v = enclosed_volume(testing::icosphere(level, 2.0, 5, -3, 1));
    const double error = v_sphere - v;
    EXPECT_GT(error, 0) << "level " << level;
    EXPECT_LT(error, previous_error / 3.5) << "level " << level;  // ~4x per level
    previous_error = error;
  }
  EXPECT_LT(previous_error, 2e-3 * v_sphere);
  const double v_torus = 2 * kPi * kPi * 3.0 * 1.0;  // 2 pi^2 R r^2
  EXPECT_NEAR(enclosed_volume(testing::torus(200, 100, 3.0, 1.0)), v_torus, 2e-3 * v_torus);
}

TEST(EnclosedVolume, EmptyIsZero) { EXPECT_EQ(enclosed_volume(SurfaceMesh{}), 0.0); }

}  // namespace
}  // namespace vm
