#include "core/mesh/surface_distance.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include "core/geom/closest_point.h"
#include "tests/support/icosphere.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

// The unit square [0, 1]^2 at z = 0 as two triangles.
SurfaceMesh square() {
  SurfaceMesh m;
  m.points = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  m.triangles = {0, 1, 2, 0, 2, 3};
  return m;
}

double brute_force(const SurfaceMesh& m, const double* q) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    double c[3];
    best =
        std::min(best, closest_point_on_triangle(q, &m.points[3 * size_t(m.triangles[3 * t])],
                                                 &m.points[3 * size_t(m.triangles[3 * t + 1])],
                                                 &m.points[3 * size_t(m.triangles[3 * t + 2])], c));
  }
  return std::sqrt(best);
}

TEST(SurfaceDistance, ExactOnASquare) {
  const SurfaceMesh m = square();
  const TriangleBvh bvh = build_triangle_bvh(m);
  const double above[3] = {0.3, 0.4, 2.0};
  SurfacePoint p = closest_surface_point(m, bvh, above);
  EXPECT_EQ(p.distance, 2.0);
  EXPECT_NEAR(p.point[0], 0.3, 1e-15);
  EXPECT_NEAR(p.point[1], 0.4, 1e-15);
  EXPECT_EQ(p.point[2], 0.0);
  EXPECT_EQ(p.triangle, 1);  // above the triangle 0, 2, 3 (y > x)
  const double side[3] = {2.0, 0.5, 0.0};
  EXPECT_EQ(closest_surface_point(m, bvh, side).distance, 1.0);
  const double corner[3] = {2.0, 2.0, 1.0};
  EXPECT_NEAR(closest_surface_point(m, bvh, corner).distance, std::sqrt(3.0), 1e-15);
  const double on[3] = {0.25, 0.75, 0.0};
  EXPECT_EQ(closest_surface_point(m, bvh, on).distance, 0.0);

  const std::vector<double> pts = {0.3, 0.4, 2.0, 2.0, 0.5, 0.0, 0.5, 0.5, -0.5};
  DistanceReport r = distances_to_surface(m, pts, true);
  EXPECT_EQ(r.count, 3u);
  ASSERT_EQ(r.per_point.size(), 3u);
  EXPECT_EQ(r.per_point[0], 2.0);
  EXPECT_EQ(r.per_point[1], 1.0);
  EXPECT_EQ(r.per_point[2], 0.5);
  EXPECT_EQ(r.max, 2.0);
  EXPECT_EQ(r.argmax, 0u);
  EXPECT_NEAR(r.mean, 3.5 / 3, 1e-15);
  EXPECT_TRUE(distances_to_surface(m, pts).per_point.empty());
}

TEST(SurfaceDistance, MatchesBruteForceOnATorus) {
  const SurfaceMesh m = testing::torus(60, 30, 3.0, 1.0);
  const TriangleBvh bvh = build_triangle_bvh(m);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-5, 5);
  for (int i = 0; i < 2000; ++i) {
    const double q[3] = {u(rng), u(rng), 0.4 * u(rng)};
    const SurfacePoint p = closest_surface_point(m, bvh, q);
    EXPECT_EQ(p.distance, brute_force(m, q)) << "query " << i;
    ASSERT_GE(p.triangle, 0);
    const double back = std::sqrt(std::pow(p.point[0] - q[0], 2) + std::pow(p.point[1] - q[1], 2) +
                                  std::pow(p.point[2] - q[2], 2));
    EXPECT_NEAR(back, p.distance, 1e-12);
  }
}

TEST(SurfaceDistance, VerticesAreOnTheSurfaceAndOffsetsMeasured) {
  const SurfaceMesh s = testing::icosphere(4, 2.0);
  EXPECT_EQ(distances_to_surface(s, s.points).max, 0.0);
  // Points on the sphere of radius 3: 1 away, plus at most the sag of the
  // inscribed polyhedron.
  std::vector<double> out;
  for (size_t i = 0; i < s.points.size(); ++i) out.push_back(1.5 * s.points[i]);
  const DistanceReport r = distances_to_surface(s, out);
  EXPECT_NEAR(r.mean, 1.0, 1e-12);  // vertices project onto vertices
  EXPECT_NEAR(r.max, 1.0, 1e-12);
}

TEST(SurfaceDistance, EmptySurfaceIsInfinitelyFar) {
  const std::vector<double> pts = {0, 0, 0};
  EXPECT_TRUE(std::isinf(distances_to_surface(SurfaceMesh{}, pts).max));
  EXPECT_EQ(distances_to_surface(square(), {}).count, 0u);
}

TEST(SurfaceDistance, TimingOnALargeSurface) {
  const SurfaceMesh m = testing::torus(500, 200, 3.0, 1.0);  // 200k triangles
  // The use case: vertices of another mesh of the same surface (here the
  // torus at another resolution, within its sag of this one) and points
  // near it.
  const SurfaceMesh other = testing::torus(400, 150, 3.0, 1.0);
  std::vector<double> q = other.points;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (size_t i = 0; i < 40000; ++i) {
    const size_t v = 3 * (i * 7919 % other.num_vertices());
    q.insert(q.end(), {other.points[v] + u(rng), other.points[v + 1] + u(rng),
                       other.points[v + 2] + u(rng)});
  }
  const auto t0 = std::chrono::steady_clock::now();
  const DistanceReport r = distances_to_surface(m, q);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GT(r.max, 0.0);
  EXPECT_LT(r.max, 0.1);
  std::cout << "[ info ] " << r.count << " distances to " << m.num_triangles()
            << " triangles (build included): " << s << " s\n";
}

}  // namespace
}  // namespace vm
