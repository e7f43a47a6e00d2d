// Hole filling (core/prepare/fill_holes) and the manifold repair
// (core/mesh/manifold_repair) on small analytic surfaces.
#include "core/prepare/fill_holes.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/geom/vec3.h"
#include "core/mesh/manifold_repair.h"
#include "core/mesh/repair.h"
#include "core/mesh/topology.h"
#include "tests/support/icosphere.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

/// An icosphere with the triangles near the north pole removed.
SurfaceMesh sphere_with_hole(double hole_radius, std::vector<int32_t>* labels) {
  SurfaceMesh m = testing::icosphere(3);
  std::vector<uint8_t> remove(m.num_triangles(), 0);
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    Vec3 c{};
    for (int k = 0; k < 3; ++k) c = c + (1.0 / 3) * at(m.points, m.triangles[3 * t + size_t(k)]);
    remove[t] = norm(c - Vec3{0, 0, 1}) < hole_radius;
  }
  labels->assign(m.num_triangles(), 7);
  remove_triangles(m, remove, labels);
  return m;
}

TEST(FillHoles, ClosesALoopWithWellShapedTrianglesThatTakeTheLabel) {
  for (double radius : {0.1, 0.3, 0.5}) {
    std::vector<int32_t> labels;
    SurfaceMesh m = sphere_with_hole(radius, &labels);
    const TopologyReport before = analyze_topology(m);
    ASSERT_EQ(before.openings.size(), 1u) << radius;
    const auto fills = fill_holes(m, {before.openings[0].loop}, &labels);
    ASSERT_EQ(fills.size(), 1u);
    EXPECT_TRUE(fills[0].filled);
    EXPECT_GT(fills[0].min_angle, 20)
        << radius << ": " << before.openings[0].loop.size() << " rim vertices";
    EXPECT_EQ(labels.size(), m.num_triangles());
    for (int32_t l : labels) EXPECT_EQ(l, 7);
    const TopologyReport after = analyze_topology(m);
    EXPECT_TRUE(after.closed);
    EXPECT_EQ(after.genus, 0);
    EXPECT_EQ(after.nonmanifold_edges, 0u);
    // Consistently oriented with the rest: nothing to flip.
    RepairStats stats;
    orient_consistently(m, stats);
    EXPECT_TRUE(stats.orientable);
    EXPECT_EQ(stats.flipped, 0u) << radius;
  }
}

TEST(ManifoldRepair, TwoSheetsTouchingAtAVertexGetOneCopy) {
  // Two tetrahedra sharing vertex 0 only.
  SurfaceMesh m = testing::tetrahedron();
  const size_t n = m.num_vertices();
  for (size_t v = 1; v < n; ++v) {
    const Vec3 p = at(m.points, int32_t(v));
    m.points.insert(m.points.end(), {-p[0], -p[1], -p[2]});
  }
  const size_t nt = m.num_triangles();
  for (size_t i = 0; i < 3 * nt; ++i) {
    const int32_t v = m.triangles[i];
    m.triangles.push_back(v == 0 ? 0 : v + int32_t(n) - 1);
  }
  EXPECT_EQ(analyze_topology(m).nonmanifold_vertices, 1u);
  ManifoldRepairStats stats;
  split_nonmanifold_vertices(m, stats);
  EXPECT_EQ(stats.vertices_split, 1u);
  EXPECT_EQ(stats.vertex_copies, 1u);
  const TopologyReport t = analyze_topology(m);
  EXPECT_EQ(t.nonmanifold_vertices, 0u);
  EXPECT_EQ(t.components, 2);
}

TEST(ManifoldRepair, AFinIsRemovedWithItsLabel) {
  SurfaceMesh m = testing::tetrahedron();
  m.points.insert(m.points.end(), {0.5, -1, 0.5});
  m.triangles.insert(m.triangles.end(), {0, 1, 4});
  std::vector<int32_t> labels = {1, 2, 3, 4, 9};
  ManifoldRepairStats stats;
  split_nonmanifold_edges(m, &labels, stats);
  EXPECT_EQ(stats.fins_removed, 1u);
  EXPECT_EQ(stats.edges_split, 0u);
  EXPECT_EQ(m.num_triangles(), 4u);
  EXPECT_EQ(m.num_vertices(), 4u);
  EXPECT_EQ(labels, (std::vector<int32_t>{1, 2, 3, 4}));
  EXPECT_TRUE(analyze_topology(m).closed);
}

}  // namespace
}  // namespace vm
