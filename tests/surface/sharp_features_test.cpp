#include "core/surface/sharp_features.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "core/mesh/adjacency.h"
#include "core/mesh/surface_distance.h"
#include "core/mesh/topology.h"
#include "core/quality/triangle_quality.h"
#include "core/surface/remesh_surface.h"
#include "tests/support/icosphere.h"
#include "tests/support/remesh_options.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

size_t count_edges(const std::vector<uint8_t>& feature) {
  return size_t(std::accumulate(feature.begin(), feature.end(), 0)) / 2;
}

TEST(SharpFeatures, CapRimsOfAClosedCylinderAreFeatures) {
  const int n = 32;
  const SurfaceMesh m = testing::capped_tube(n, 16, 1.0, 4.0);
  const TriangleAdjacency adj = build_adjacency(m);
  const std::vector<double> h(m.num_vertices(), 0.2);
  const std::vector<uint8_t> f = sharp_feature_edges(m, adj, h, 60);
  EXPECT_EQ(count_edges(f), size_t(2 * n));  // both rims, nothing else
  for (size_t he = 0; he < f.size(); ++he) {
    if (!f[he]) continue;
    const double za = m.points[3 * size_t(half_edge_from(m, int32_t(he))) + 2];
    const double zb = m.points[3 * size_t(half_edge_to(m, int32_t(he))) + 2];
    EXPECT_TRUE((za == 0 && zb == 0) || (za == 4 && zb == 4));
  }
  EXPECT_EQ(count_edges(sharp_feature_edges(m, adj, h, 180)), 0u);  // off
}

TEST(SharpFeatures, SmoothSurfacesAndIsolatedSpikesHaveNone) {
  // A sphere with one vertex pulled out: a sharp spot, a feature at a size
  // finer than it, dropped at a size much coarser; an open tube has none.
  SurfaceMesh s = testing::icosphere(3);
  for (int k = 0; k < 3; ++k) s.points[size_t(k)] *= 1.5;
  std::vector<double> h(s.num_vertices(), 0.2);
  EXPECT_GT(count_edges(sharp_feature_edges(s, build_adjacency(s), h, 60)), 0u);
  h.assign(s.num_vertices(), 2.0);
  EXPECT_EQ(count_edges(sharp_feature_edges(s, build_adjacency(s), h, 60)), 0u);
  const SurfaceMesh t = testing::open_tube(32, 16);
  h.assign(t.num_vertices(), 0.2);
  EXPECT_EQ(count_edges(sharp_feature_edges(t, build_adjacency(t), h, 60)), 0u);
}

TEST(SharpFeatures, RemeshingKeepsTheRimsOfACappedCylinder) {
  // A closed cylinder (flat caps, 90-degree rims) remeshed at h = 0.2: the
  // rims stay sharp, so every input vertex stays close to the output, and
  // the output vertices on the rims lie on the rim circles.
  const SurfaceMesh in = testing::capped_tube(64, 32, 1.0, 4.0);
  RemeshOptions o = testing::uniform_remesh(0.2);
  RemeshStats stats;
  auto r = remesh_surface(in, o, &stats);
  ASSERT_TRUE(r.ok()) << r.message();
  const RemeshedSurface& out = r.value();
  EXPECT_EQ(stats.feature_edges, 128u);
  const TopologyReport t = analyze_topology(out.mesh);
  EXPECT_TRUE(t.closed);
  EXPECT_EQ(t.genus, 0);
  size_t on_rims = 0;
  for (size_t v = 0; v < out.mesh.num_vertices(); ++v) {
    if (!out.on_feature[v]) continue;
    ++on_rims;
    const double* x = &out.mesh.points[3 * v];
    EXPECT_NEAR(std::hypot(x[0], x[1]), 1.0, 2e-3);  // on the input's rim polygon
    EXPECT_TRUE(std::abs(x[2]) < 1e-12 || std::abs(x[2] - 4) < 1e-12) << x[2];
  }
  EXPECT_GE(on_rims, size_t(2 * 2 * 3.14159 / 0.2 * 0.9));
  const DistanceReport gaps = distances_to_surface(out.mesh, in.points);
  EXPECT_LT(gaps.max, 0.1 * 0.2);
  const QualityStats q = quality_stats(triangle_qualities(out.mesh));
  EXPECT_GT(q.min, 0.55);
  EXPECT_GT(q.mean, 0.97);
  // Without features the rims are cut: the gap is much larger.
  o.feature_angle_degrees = 180;
  auto cut = remesh_surface(in, o);
  ASSERT_TRUE(cut.ok()) << cut.message();
  EXPECT_GT(distances_to_surface(cut.value().mesh, in.points).max, 0.1 * 0.2);
}

}  // namespace
}  // namespace vm
