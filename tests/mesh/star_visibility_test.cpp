#include "core/mesh/star_visibility.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/test_meshes.h"

namespace vm {
namespace {

TEST(StarVisibility, FindsNeedles) {
  SurfaceMesh m = testing::square_grid(4);  // spacing 0.25
  const size_t center = 2 * 5 + 2;
  for (double v : star_visibility(m)) EXPECT_NEAR(v, 1.0, 1e-12);
  // A bump is seen from above; a needle ten spacings tall barely (its
  // triangles stand almost upright); one folded back under its base by no
  // direction.
  m.points[3 * center + 2] = 0.05;
  EXPECT_GT(star_visibility(m)[center], 0.9);
  m.points[3 * center + 2] = 2.5;
  EXPECT_LT(star_visibility(m)[center], 0.15);
  EXPECT_GT(star_visibility(m)[center], 0.0);
  m.points[3 * center] = 0.5 + 0.4;  // over and past its neighbor at x = 0.75
  m.points[3 * center + 2] = 0.01;
  EXPECT_LT(star_visibility(m)[center], 0.0);
}

TEST(StarVisibility, SeeStarKeepsTheConstraintAndTheBestDirection) {
  // Two triangles folded to normals +-60 degrees from z around the x axis:
  // from +x (which sees neither) the push reaches z, which sees both at
  // cos 60; held in the plane y = 0 it still does; held in z = 0 it cannot
  // improve and the start is kept.
  const double s = std::sqrt(3.0) / 2;
  const std::vector<double> normals = {0, s, 0.5, 0, -s, 0.5};
  const int32_t star[2] = {0, 1};
  double d[3] = {1, 0, 0};
  const double free_w = see_star(star, 2, normals.data(), d, 0.3, 40, [](double*) {});
  EXPECT_GT(free_w, 0.3);
  EXPECT_NEAR(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], 1, 1e-12);
  double in_xz[3] = {1, 0, 0};
  const double xz_w =
      see_star(star, 2, normals.data(), in_xz, 0.3, 40, [](double* x) { x[1] = 0; });
  EXPECT_GT(xz_w, 0.3);
  EXPECT_EQ(in_xz[1], 0.0);
  double in_xy[3] = {1, 0, 0};
  const double xy_w =
      see_star(star, 2, normals.data(), in_xy, 0.3, 40, [](double* x) { x[2] = 0; });
  EXPECT_LE(xy_w, 0.0);
  EXPECT_EQ(in_xy[2], 0.0);
}

}  // namespace
}  // namespace vm
