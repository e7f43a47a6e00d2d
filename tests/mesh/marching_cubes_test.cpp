#include "core/mesh/marching_cubes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/mesh/adjacency.h"
#include "core/mesh/topology.h"

namespace vm {
namespace {

// Samples f on a cube grid [-L, L]^3 with n points per axis.
template <class F>
SurfaceMesh extract(F f, int n, double L) {
  GridSpec g;
  g.nx = g.ny = g.nz = n;
  g.spacing = 2 * L / (n - 1);
  for (double& o : g.origin) o = -L;
  return marching_cubes(g, [&](int k, float* plane) {
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        plane[i + n * j] = float(f(-L + g.spacing * i, -L + g.spacing * j, -L + g.spacing * k));
  });
}

double signed_volume(const SurfaceMesh& m) {
  double v = 0;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const double* a = &m.points[3 * m.triangles[3 * t]];
    const double* b = &m.points[3 * m.triangles[3 * t + 1]];
    const double* c = &m.points[3 * m.triangles[3 * t + 2]];
    v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
          a[2] * (b[0] * c[1] - b[1] * c[0])) /
         6;
  }
  return v;
}

// Closed, manifold, consistently oriented: every half-edge has an opposite
// running the other way.
void expect_closed_oriented(const SurfaceMesh& m) {
  TriangleAdjacency adj = build_adjacency(m);
  for (size_t h = 0; h < adj.opposite.size(); ++h) {
    ASSERT_GE(adj.opposite[h], 0) << "half-edge " << h << " is open or non-manifold";
    EXPECT_EQ(half_edge_from(m, int32_t(h)), half_edge_to(m, adj.opposite[h]));
  }
}

TEST(MarchingCubes, SphereIsClosedOutwardAndAccurate) {
  const double r = 0.8;
  SurfaceMesh m = extract(
      [&](double x, double y, double z) { return std::sqrt(x * x + y * y + z * z) - r; }, 41, 1.0);
  ASSERT_GT(m.num_triangles(), 1000u);
  expect_closed_oriented(m);
  TopologyReport t = analyze_topology(m);
  EXPECT_EQ(t.euler_characteristic, 2);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.nonmanifold_vertices, 0u);
  double vol = signed_volume(m), exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  EXPECT_NEAR(vol, exact, 0.02 * exact);
  const double h = 2.0 / 40;
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    const double* p = &m.points[3 * v];
    EXPECT_NEAR(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), r, h);
  }
}

TEST(MarchingCubes, TorusHasEulerCharacteristicZero) {
  SurfaceMesh m = extract(
      [](double x, double y, double z) {
        double q = std::sqrt(x * x + y * y) - 0.6;
        return std::sqrt(q * q + z * z) - 0.25;
      },
      48, 1.0);
  expect_closed_oriented(m);
  TopologyReport t = analyze_topology(m);
  EXPECT_EQ(t.euler_characteristic, 0);
  EXPECT_EQ(t.genus, 1);
}

TEST(MarchingCubes, AmbiguousFacesStayWatertight) {
  // A checkerboard-like field exercises every ambiguous face configuration.
  SurfaceMesh m = extract(
      [](double x, double y, double z) {
        double r2 = x * x + y * y + z * z;
        if (r2 > 0.8) return 1.0;  // keep the inside away from the border
        return std::sin(9 * x) * std::sin(9 * y) * std::sin(9 * z) + 0.05;
      },
      37, 1.0);
  ASSERT_GT(m.num_triangles(), 100u);
  expect_closed_oriented(m);
  EXPECT_GT(signed_volume(m), 0);
}

TEST(MarchingCubes, ValuesAtZeroMakeNoDegenerateEdges) {
  // Plane x = 0 exactly through grid points.
  SurfaceMesh m = extract(
      [](double x, double y, double z) {
        return std::max({std::fabs(x), std::fabs(y), std::fabs(z)}) - 0.5;
      },
      21, 1.0);
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    int32_t a = m.triangles[3 * t], b = m.triangles[3 * t + 1], c = m.triangles[3 * t + 2];
    EXPECT_TRUE(a != b && b != c && a != c);
  }
  expect_closed_oriented(m);
}

}  // namespace
}  // namespace vm
