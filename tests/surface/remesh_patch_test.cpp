#include "core/surface/remesh_patch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "core/mesh/topology.h"
#include "core/quality/triangle_quality.h"
#include "tests/param/param_test_meshes.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

// A coarse, jittered spherical cap of the unit sphere (polar angle < 1 rad).
SurfaceMesh cap() {
  return testing::disk(30, 6, 0.35, [](double x, double y) {
    double t = std::hypot(x, y), phi = std::atan2(y, x);
    return std::array<double, 3>{std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi),
                                 std::cos(t)};
  });
}

TEST(RemeshPatch, SphericalCapWithUniformSize) {
  SurfaceMesh in = cap();
  const double h = 0.06;
  PatchRemeshStats stats;
  auto r = remesh_disk_patch(
      in, [&](const double*) { return h; }, &stats);
  ASSERT_TRUE(r.ok()) << r.message();
  const SurfaceMesh& out = r.value();
  // Topology kept: one disk.
  TopologyReport t = analyze_topology(out);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.openings.size(), 1u);
  EXPECT_EQ(t.genus, 0);
  EXPECT_EQ(t.nonmanifold_edges, 0u);
  // On the input surface (flat input facets deviate from the sphere by less
  // than their sagitta) and outward.
  for (size_t v = 0; v < out.num_vertices(); ++v) {
    const double* x = &out.points[3 * v];
    EXPECT_NEAR(std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]), 1.0, 2e-3);
  }
  std::vector<double> lengths;
  std::set<std::pair<int32_t, int32_t>> seen;
  for (size_t f = 0; f < out.num_triangles(); ++f) {
    const int32_t* v = &out.triangles[3 * f];
    const double *a = &out.points[3 * size_t(v[0])], *b = &out.points[3 * size_t(v[1])],
                 *c = &out.points[3 * size_t(v[2])];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
           w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    EXPECT_GT(n[0] * a[0] + n[1] * a[1] + n[2] * a[2], 0) << "triangle " << f << " faces inward";
    for (int k = 0; k < 3; ++k) {
      auto e = std::minmax(v[k], v[(k + 1) % 3]);
      if (!seen.insert(e).second) continue;
      const double *p = &out.points[3 * size_t(e.first)], *q = &out.points[3 * size_t(e.second)];
      lengths.push_back(std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                                  (p[2] - q[2]) * (p[2] - q[2])));
    }
  }
  std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
  EXPECT_NEAR(lengths[lengths.size() / 2], h, 0.1 * h);
  QualityStats q = quality_stats(triangle_qualities(out));
  EXPECT_GT(q.min, 0.6);
  EXPECT_GT(q.mean, 0.93);
  // Better than the input it replaces.
  QualityStats qin = quality_stats(triangle_qualities(in));
  EXPECT_GT(q.min, qin.min);
  std::cout << "[ info ] cap: " << in.num_triangles() << " -> " << out.num_triangles()
            << " triangles, gamma min " << q.min << " mean " << q.mean << " (input " << qin.min
            << " / " << qin.mean << "), conformal factor " << stats.min_conformal_factor << "-"
            << stats.max_conformal_factor << "\n";
}

TEST(RemeshPatch, GradedSizeFollowsTheField) {
  SurfaceMesh in = cap();
  auto size = [](const double* x) { return 0.03 + 0.06 * (x[0] + 1); };
  auto r = remesh_disk_patch(in, size);
  ASSERT_TRUE(r.ok()) << r.message();
  const SurfaceMesh& out = r.value();
  // Mean edge length near x = -0.6 vs near x = +0.6.
  double left = 0, right = 0;
  int nl = 0, nr = 0;
  for (size_t f = 0; f < out.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k) {
      const double* p = &out.points[3 * size_t(out.triangles[3 * f + k])];
      const double* q = &out.points[3 * size_t(out.triangles[3 * f + (k + 1) % 3])];
      double len = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                             (p[2] - q[2]) * (p[2] - q[2]));
      double mx = 0.5 * (p[0] + q[0]);
      if (std::fabs(mx + 0.6) < 0.1) left += len, ++nl;
      if (std::fabs(mx - 0.6) < 0.1) right += len, ++nr;
    }
  ASSERT_GT(nl, 0);
  ASSERT_GT(nr, 0);
  left /= nl;
  right /= nr;
  double x_left[3] = {-0.6, 0, 0}, x_right[3] = {0.6, 0, 0};
  EXPECT_NEAR(left, size(x_left), 0.2 * size(x_left));
  EXPECT_NEAR(right, size(x_right), 0.2 * size(x_right));
}

TEST(RemeshPatch, NeedsOneBoundaryLoop) {
  auto r = remesh_disk_patch(testing::open_tube(16, 8), [](const double*) { return 0.2; });
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("exactly one boundary loop, found 2"), std::string::npos);
}

}  // namespace
}  // namespace vm
