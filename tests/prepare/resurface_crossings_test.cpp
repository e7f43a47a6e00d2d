#include "core/prepare/resurface_crossings.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/mesh/adjacency.h"
#include "core/mesh/enclosed_volume.h"
#include "core/mesh/self_intersection.h"
#include "core/mesh/topology.h"
#include "tests/support/icosphere.h"
#include "tests/support/phantoms.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

/// Manifold (every edge two triangles, or one on an opening), no crossing.
void expect_clean(const SurfaceMesh& m) {
  const TriangleAdjacency adj = build_adjacency(m);
  EXPECT_EQ(adj.num_nonmanifold_edges, 0u);
  EXPECT_EQ(find_self_intersections(m).pairs, 0u);
  const TopologyReport t = analyze_topology(m, adj);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.nonmanifold_vertices, 0u);
}

TEST(ResurfaceCrossings, TwoOverlappingSpheresBecomeTheirUnion) {
  const double r = 1, d = 0.8;
  SurfaceMesh m = testing::joined(testing::icosphere(4, r), testing::icosphere(4, r, d, 0, 0));
  ASSERT_GT(find_self_intersections(m).pairs, 0u);
  std::vector<int32_t> labels(m.num_triangles(), 0);
  std::fill(labels.begin() + long(m.num_triangles() / 2), labels.end(), 1);
  const ResurfaceReport report = resurface_crossings(m, &labels);
  ASSERT_EQ(report.places.size(), 1u);
  EXPECT_TRUE(report.places[0].resolved) << report.places[0].why;
  EXPECT_TRUE(report.left.empty());
  expect_clean(m);
  const TopologyReport t = analyze_topology(m);
  EXPECT_TRUE(t.closed);
  EXPECT_EQ(t.genus, 0);
  EXPECT_EQ(labels.size(), m.num_triangles());
  // The union of two balls: both balls less their lens.
  const double lens = std::numbers::pi * (4 * r + d) * (2 * r - d) * (2 * r - d) / 12;
  const double want = 2 * 4.0 / 3 * std::numbers::pi * r * r * r - lens;
  EXPECT_NEAR(enclosed_volume(m), want, 0.02 * want);
  // The place is where the spheres cross: their circle at x = d / 2.
  EXPECT_NEAR(report.places[0].where[0], d / 2, 0.2);
}

TEST(ResurfaceCrossings, AnInsideOutFileStaysInsideOut) {
  SurfaceMesh m = testing::joined(testing::icosphere(3, 1), testing::icosphere(3, 1, 0.8, 0, 0));
  for (size_t t = 0; t < m.num_triangles(); ++t)
    std::swap(m.triangles[3 * t + 1], m.triangles[3 * t + 2]);
  const ResurfaceReport report = resurface_crossings(m, nullptr);
  ASSERT_EQ(report.resolved(), 1u);
  expect_clean(m);
  EXPECT_LT(enclosed_volume(m), -5.0);  // still facing inward, and whole
}

TEST(ResurfaceCrossings, TwoVesselsThatPassIntoEachOtherKeepTheirFourOpenings) {
  PhantomOptions o;
  o.kind = PhantomKind::kCrossing;
  o.voxel = 0.15;
  PhantomTruth truth;
  SurfaceMesh m = testing::phantom(o, &truth);
  ASSERT_GT(find_self_intersections(m).pairs, 0u);
  EXPECT_EQ(analyze_topology(m).components, 2);
  const ResurfaceReport report = resurface_crossings(m, nullptr);
  EXPECT_EQ(report.resolved(), report.places.size());
  expect_clean(m);
  const TopologyReport t = analyze_topology(m);
  ASSERT_EQ(t.openings.size(), 4u);
  EXPECT_EQ(t.genus, 0);
  for (const Opening& op : t.openings) {
    const size_t k = testing::nearest_truth_opening(truth, op.centroid.data());
    EXPECT_NEAR(op.radius, truth.opening_radii[k], 0.1 * truth.opening_radii[k]);
  }
}

TEST(ResurfaceCrossings, LeavesACleanSurfaceAlone) {
  SurfaceMesh m = testing::phantom(PhantomKind::kBifurcation, true, 0.15);
  const SurfaceMesh before = m;
  const ResurfaceReport report = resurface_crossings(m, nullptr);
  EXPECT_EQ(report.pairs, 0u);
  EXPECT_TRUE(report.places.empty());
  EXPECT_EQ(m.points, before.points);
  EXPECT_EQ(m.triangles, before.triangles);
}

TEST(ResurfaceCrossings, DoesNotReachAcrossAnOpening) {
  // A ball through the wall at the open end of a tube: the union is not defined
  // across the opening, so the place is left for the trimming.
  PhantomOptions o;
  o.kind = PhantomKind::kTube;
  o.voxel = 0.15;
  PhantomTruth truth;
  SurfaceMesh tube = testing::phantom(o, &truth);
  const auto& c = truth.opening_centers[0];
  SurfaceMesh m = testing::joined(tube, testing::icosphere(3, 0.5, c[0] + 0.9, c[1], c[2]));
  const size_t before = m.num_triangles();
  const ResurfaceReport report = resurface_crossings(m, nullptr);
  ASSERT_FALSE(report.places.empty());
  EXPECT_FALSE(report.places[0].resolved)
      << point_text(report.places[0].where) << " " << point_text(report.places[0].box_min) << " "
      << point_text(report.places[0].box_max) << " " << point_text(Vec3(c));
  EXPECT_TRUE(report.places[0].near_opening);
  EXPECT_EQ(m.num_triangles(), before);
  EXPECT_FALSE(report.left.empty());
}

}  // namespace
}  // namespace vm
