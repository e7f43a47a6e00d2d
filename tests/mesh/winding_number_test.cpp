#include "core/mesh/winding_number.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tests/support/icosphere.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

TEST(WindingNumber, IsOneInsideAndZeroOutsideAClosedSurface) {
  const SurfaceMesh s = testing::icosphere(3, 1.0);
  const WindingNumberTree tree = build_winding_number_tree(s);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2, 2);
  int checked = 0;
  for (int i = 0; i < 400; ++i) {
    const double q[3] = {u(rng), u(rng), u(rng)};
    const double r = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    if (std::abs(r - 1) < 0.05) continue;  // the polyhedron differs from the sphere there
    const double want = r < 1 ? 1.0 : 0.0;
    EXPECT_NEAR(winding_number_exact(s, q), want, 1e-9) << r;
    EXPECT_NEAR(winding_number(s, tree, q), want, 0.02) << r;
    ++checked;
  }
  EXPECT_GT(checked, 300);
}

TEST(WindingNumber, CountsOverlappingShellsAndTheirOrientation) {
  SurfaceMesh a = testing::icosphere(2, 1.0);
  const SurfaceMesh b = testing::icosphere(2, 1.0, 0.8, 0, 0);
  const SurfaceMesh both = testing::joined(a, b);
  const WindingNumberTree tree = build_winding_number_tree(both);
  const double in_both[3] = {0.4, 0, 0}, in_a[3] = {-0.6, 0, 0}, out[3] = {3, 0, 0};
  EXPECT_NEAR(winding_number(both, tree, in_both), 2, 0.02);
  EXPECT_NEAR(winding_number(both, tree, in_a), 1, 0.02);
  EXPECT_NEAR(winding_number(both, tree, out), 0, 0.02);
  // Inward-facing: the signs turn.
  for (size_t t = 0; t < a.num_triangles(); ++t)
    std::swap(a.triangles[3 * t + 1], a.triangles[3 * t + 2]);
  EXPECT_NEAR(winding_number_exact(a, in_a), -1, 1e-9);
}

TEST(WindingNumber, AnOpenSheetGivesAFractionThatFallsAwayFromIt) {
  // The upper half of a sphere: at its centre it subtends half the sphere.
  const SurfaceMesh s = testing::icosphere(3, 1.0);
  SurfaceMesh half;
  half.points = s.points;
  for (size_t t = 0; t < s.num_triangles(); ++t) {
    double z = 0;
    for (int k = 0; k < 3; ++k) z += s.points[3 * size_t(s.triangles[3 * t + size_t(k)]) + 2];
    if (z > 0)
      half.triangles.insert(half.triangles.end(), &s.triangles[3 * t], &s.triangles[3 * t] + 3);
  }
  const WindingNumberTree tree = build_winding_number_tree(half);
  const double centre[3] = {0, 0, 0}, high[3] = {0, 0, 0.9}, far[3] = {0, 0, -5};
  EXPECT_NEAR(winding_number(half, tree, centre), 0.5, 0.03);
  EXPECT_GT(winding_number(half, tree, high), 0.8);
  EXPECT_LT(std::abs(winding_number(half, tree, far)), 0.05);
}

}  // namespace
}  // namespace vm
