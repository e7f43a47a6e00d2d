#include "core/mesh/region_submesh.h"

#include <gtest/gtest.h>

#include <array>

namespace vm {
namespace {

/// (b - a) x (c - a) . (d - a) of four points of `m`.
double orientation(const VolumeMesh& m, int32_t a, int32_t b, int32_t c, const double* d) {
  const auto p = [&](int32_t v, int k) { return m.points[3 * size_t(v) + size_t(k)]; };
  const double u[3] = {p(b, 0) - p(a, 0), p(b, 1) - p(a, 1), p(b, 2) - p(a, 2)};
  const double w[3] = {p(c, 0) - p(a, 0), p(c, 1) - p(a, 1), p(c, 2) - p(a, 2)};
  const double x[3] = {d[0] - p(a, 0), d[1] - p(a, 1), d[2] - p(a, 2)};
  return (u[1] * w[2] - u[2] * w[1]) * x[0] + (u[2] * w[0] - u[0] * w[2]) * x[1] +
         (u[0] * w[1] - u[1] * w[0]) * x[2];
}

TEST(RegionSubmesh, TwoRegionsShareTheInterfaceEachOrientedOutward) {
  // Two tetrahedra on the triangle (0, 1, 2): region 0 below (apex 3 at
  // z = -1), region 2 above (apex 4 at z = 1); the interface is tagged 5,
  // each outer face tagged by its tetrahedron's apex.
  VolumeMesh m;
  m.points = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.2, -1, 0.2, 0.2, 1};
  m.tets = {0, 2, 1, 3, 0, 1, 2, 4};
  m.tet_region = {0, 2};
  m.triangles = {0, 1, 2, 0, 1, 3, 0, 1, 4};
  m.triangle_tag = {5, 3, 4};
  const VolumeMesh below = region_submesh(m, {0});
  const VolumeMesh above = region_submesh(m, {2});
  ASSERT_EQ(below.num_tets(), 1u);
  ASSERT_EQ(above.num_tets(), 1u);
  EXPECT_EQ(below.num_vertices(), 4u);  // only its own points
  EXPECT_EQ(above.num_vertices(), 4u);
  EXPECT_EQ(below.triangle_tag, (std::vector<int32_t>{5, 3}));
  EXPECT_EQ(above.triangle_tag, (std::vector<int32_t>{5, 4}));
  // The interface points out of each part: the other part's apex is in front.
  for (const VolumeMesh* part : {&below, &above}) {
    const int32_t* t = &part->triangles[0];
    const int32_t* cell = &part->tets[0];
    int32_t apex = -1;
    for (int k = 0; k < 4; ++k)
      if (cell[k] != t[0] && cell[k] != t[1] && cell[k] != t[2]) apex = cell[k];
    ASSERT_GE(apex, 0);
    EXPECT_LT(orientation(*part, t[0], t[1], t[2], &part->points[3 * size_t(apex)]), 0);
  }
  // The same coordinates on both sides.
  for (int k = 0; k < 3; ++k) {
    std::array<double, 3> a{}, b{};
    for (int c = 0; c < 3; ++c) {
      a[size_t(c)] = below.points[3 * size_t(below.triangles[size_t(k)]) + size_t(c)];
    }
    bool found = false;
    for (int j = 0; j < 3; ++j) {
      for (int c = 0; c < 3; ++c)
        b[size_t(c)] = above.points[3 * size_t(above.triangles[size_t(j)]) + size_t(c)];
      found = found || a == b;
    }
    EXPECT_TRUE(found) << k;
  }
}

}  // namespace
}  // namespace vm
