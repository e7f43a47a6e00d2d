#include "core/mesh/topology.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/mesh/repair.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

TEST(Topology, ClosedTetrahedron) {
  TopologyReport r = analyze_topology(testing::tetrahedron());
  EXPECT_EQ(r.vertices, 4u);
  EXPECT_EQ(r.edges, 6u);
  EXPECT_EQ(r.euler_characteristic, 2);
  EXPECT_EQ(r.genus, 0);
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.openings.empty());
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.nonmanifold_edges, 0u);
}

TEST(Topology, TubeHasTwoOpeningsWithTheTrueRadius) {
  const int n = 64;
  TopologyReport r = analyze_topology(testing::open_tube(n, 10, 2.0, 5.0));
  EXPECT_EQ(r.genus, 0);
  EXPECT_FALSE(r.closed);
  ASSERT_EQ(r.openings.size(), 2u);
  EXPECT_EQ(r.boundary_edges, size_t(2 * n));
  // Inscribed polygon: perimeter 2 n R sin(pi/n), area n R^2 sin(2pi/n)/2.
  double perim = 2 * n * 2.0 * std::sin(std::numbers::pi / n);
  double radius = std::sqrt(n * 4.0 * std::sin(2 * std::numbers::pi / n) / 2 / std::numbers::pi);
  for (const Opening& op : r.openings) {
    EXPECT_NEAR(op.perimeter, perim, 1e-9);
    EXPECT_NEAR(op.radius, radius, 1e-9);
    EXPECT_EQ(op.loop.size(), size_t(n));
    EXPECT_NEAR(op.centroid[0], 0, 1e-12);
    EXPECT_NEAR(op.centroid[1], 0, 1e-12);
  }
  // Outward cap normals: -z at z = 0, +z at z = 5.
  for (const Opening& op : r.openings) {
    double expected = op.centroid[2] < 1 ? -1 : 1;
    EXPECT_NEAR(op.normal[2], expected, 1e-12);
  }
}

TEST(Topology, TorusHasGenusOne) {
  TopologyReport r = analyze_topology(testing::torus(24, 12));
  EXPECT_EQ(r.euler_characteristic, 0);
  EXPECT_EQ(r.genus, 1);
  EXPECT_TRUE(r.closed);
}

TEST(Topology, TorusWithTwoHolesHasGenusOneAndTwoOpenings) {
  SurfaceMesh t = testing::torus(24, 12);
  // Remove two far-apart triangles: two openings, genus stays 1.
  t.triangles.erase(t.triangles.begin() + 3 * 300, t.triangles.begin() + 3 * 301);
  t.triangles.erase(t.triangles.begin() + 3 * 10, t.triangles.begin() + 3 * 11);
  TopologyReport r = analyze_topology(t);
  EXPECT_EQ(r.openings.size(), 2u);
  EXPECT_EQ(r.genus, 1);
}

TEST(Topology, ComponentsAreCountedLargestFirst) {
  SurfaceMesh a = testing::open_tube(8, 3);
  SurfaceMesh b = testing::tetrahedron();
  int32_t off = int32_t(a.num_vertices());
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  for (int32_t v : b.triangles) a.triangles.push_back(v + off);
  TopologyReport r = analyze_topology(a);
  EXPECT_EQ(r.components, 2);
  ASSERT_EQ(r.component_triangles.size(), 2u);
  EXPECT_EQ(r.component_triangles[0], 48u);
  EXPECT_EQ(r.component_triangles[1], 4u);
  EXPECT_EQ(r.genus, 0);  // both genus 0
  SurfaceMesh big = extract_component(a, r, 0);
  EXPECT_EQ(big.num_triangles(), 48u);
  EXPECT_EQ(big.num_vertices(), 32u);
}

TEST(Topology, NonManifoldEdgeIsFoundAndGenusUndefined) {
  SurfaceMesh m = testing::tetrahedron();
  // A fin: third triangle on edge (0, 1).
  m.points.insert(m.points.end(), {0.5, -1, 0.5});
  m.triangles.insert(m.triangles.end(), {0, 1, 4});
  TopologyReport r = analyze_topology(m);
  EXPECT_EQ(r.nonmanifold_edges, 1u);
  EXPECT_EQ(r.genus, -1);
  EXPECT_NEAR(r.nonmanifold_edge_example[0], 0.5, 1e-12);
}

TEST(Topology, BowTieVertexSplitsLoops) {
  // Two triangles touching at one vertex: one component, a non-manifold
  // vertex, and two boundary loops of 3 vertices each.
  SurfaceMesh m;
  m.points = {0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0};
  m.triangles = {0, 1, 2, 0, 3, 4};
  TopologyReport r = analyze_topology(m);
  EXPECT_EQ(r.nonmanifold_vertices, 1u);
  EXPECT_EQ(r.components, 1);
  ASSERT_EQ(r.openings.size(), 2u);
  EXPECT_EQ(r.openings[0].loop.size(), 3u);
  EXPECT_EQ(r.openings[1].loop.size(), 3u);
}

TEST(Repair, OrientationIsMadeConsistentAndOutward) {
  SurfaceMesh t = testing::torus(16, 8);
  testing::flip_triangle(t, 3);
  testing::flip_triangle(t, 77);
  RepairStats stats;
  orient_consistently(t, stats);
  EXPECT_TRUE(stats.orientable);
  EXPECT_EQ(stats.flipped, 2u);
  EXPECT_EQ(t.triangles, testing::torus(16, 8).triangles);

  // Entirely inside-out tube: every triangle is reversed.
  SurfaceMesh tube = testing::open_tube(12, 4);
  for (size_t i = 0; i < tube.num_triangles(); ++i) testing::flip_triangle(tube, i);
  RepairStats s2;
  orient_consistently(tube, s2);
  EXPECT_EQ(s2.flipped, tube.num_triangles());
  EXPECT_EQ(tube.triangles, testing::open_tube(12, 4).triangles);
}

TEST(Repair, MobiusStripIsNotOrientable) {
  SurfaceMesh m;
  const int n = 12;
  for (int i = 0; i < n; ++i) {
    double u = 2 * std::numbers::pi * i / n;
    for (int s = -1; s <= 1; s += 2) {
      double w = 0.3 * s;
      m.points.insert(m.points.end(),
                      {(1 + w * std::cos(u / 2)) * std::cos(u),
                       (1 + w * std::cos(u / 2)) * std::sin(u), w * std::sin(u / 2)});
    }
  }
  for (int i = 0; i < n; ++i) {
    int32_t a = 2 * i, b = 2 * i + 1;
    int32_t c = i + 1 < n ? 2 * (i + 1) : 1, d = i + 1 < n ? 2 * (i + 1) + 1 : 0;
    m.triangles.insert(m.triangles.end(), {a, c, b, b, c, d});
  }
  RepairStats stats;
  orient_consistently(m, stats);
  EXPECT_FALSE(stats.orientable);
}

TEST(Repair, DegenerateAndDuplicateTrianglesAreRemoved) {
  SurfaceMesh m = testing::tetrahedron();
  m.triangles.insert(m.triangles.end(), {0, 0, 1});  // repeated vertex
  m.triangles.insert(m.triangles.end(), {1, 0, 2});  // duplicate of 0 2 1
  m.points.insert(m.points.end(), {5, 5, 5});        // vertex 4, unused
  RepairStats stats;
  remove_degenerate_and_duplicates(m, stats);
  EXPECT_EQ(stats.degenerate_removed, 1u);
  EXPECT_EQ(stats.duplicates_removed, 1u);
  EXPECT_EQ(stats.unused_vertices_removed, 1u);
  EXPECT_EQ(m.triangles, testing::tetrahedron().triangles);
  EXPECT_EQ(m.num_vertices(), 4u);
}

TEST(Repair, FlatTriangleIsRemovedWithoutOpeningTheSurface) {
  // Tetrahedron whose edge 0-1 carries a midpoint 4 on one side: the face
  // (0, 1, 3) becomes (0, 4, 3) + (4, 1, 3) and a flat sliver (0, 1, 4)
  // fills the gap between edge 0-1 of face (0, 2, 1) and the split edge.
  SurfaceMesh m = testing::tetrahedron();
  m.points.insert(m.points.end(), {0.5, 0, 0});
  m.triangles = {0, 2, 1, 0, 4, 3, 4, 1, 3, 0, 3, 2, 1, 2, 3, 0, 1, 4};
  ASSERT_TRUE(analyze_topology(m).closed);
  RepairStats stats;
  remove_degenerate_and_duplicates(m, stats);
  EXPECT_EQ(stats.collinear_repaired, 1u);
  EXPECT_EQ(stats.degenerate_removed, 0u);
  EXPECT_EQ(m.num_triangles(), 6u);
  TopologyReport r = analyze_topology(m);
  EXPECT_TRUE(r.closed);
  EXPECT_EQ(r.genus, 0);
  EXPECT_EQ(r.nonmanifold_edges, 0u);
  // Orientation kept: every shared edge runs both ways.
  TriangleAdjacency adj = build_adjacency(m);
  for (size_t h = 0; h < adj.opposite.size(); ++h)
    EXPECT_EQ(half_edge_from(m, int32_t(h)), half_edge_to(m, adj.opposite[h]));
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const double* a = &m.points[3 * m.triangles[3 * t]];
    const double* b = &m.points[3 * m.triangles[3 * t + 1]];
    const double* c = &m.points[3 * m.triangles[3 * t + 2]];
    double u[3], v[3];
    for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], v[k] = c[k] - a[k];
    double cross = std::abs(u[1] * v[2] - u[2] * v[1]) + std::abs(u[2] * v[0] - u[0] * v[2]) +
                   std::abs(u[0] * v[1] - u[1] * v[0]);
    EXPECT_GT(cross, 0) << "triangle " << t << " is flat";
  }
}

}  // namespace
}  // namespace vm

namespace vm {
namespace {

TEST(Adjacency, OppositeHalfEdgesAreSymmetricAndReversed) {
  SurfaceMesh t = testing::torus(12, 8);
  TriangleAdjacency adj = build_adjacency(t);
  EXPECT_EQ(adj.num_edges, 3 * t.num_triangles() / 2);
  for (size_t h = 0; h < adj.opposite.size(); ++h) {
    int32_t o = adj.opposite[h];
    ASSERT_GE(o, 0);
    EXPECT_EQ(adj.opposite[o], int32_t(h));
    EXPECT_EQ(half_edge_from(t, int32_t(h)), half_edge_to(t, o));
    EXPECT_EQ(half_edge_to(t, int32_t(h)), half_edge_from(t, o));
  }
}

TEST(Adjacency, RemapAfterFlipsEqualsRebuild) {
  SurfaceMesh t = testing::open_tube(10, 6);
  std::vector<uint8_t> flipped(t.num_triangles(), 0);
  for (size_t i = 0; i < flipped.size(); i += 3) flipped[i] = 1;
  TriangleAdjacency adj = build_adjacency(t);
  for (size_t i = 0; i < flipped.size(); ++i)
    if (flipped[i]) testing::flip_triangle(t, i);
  remap_after_flips(adj, flipped);
  EXPECT_EQ(adj.opposite, build_adjacency(t).opposite);
}

TEST(Repair, OrientReturnsTheAdjacencyOfTheResult) {
  SurfaceMesh tube = testing::open_tube(12, 4);
  for (size_t i = 0; i < tube.num_triangles(); i += 2) testing::flip_triangle(tube, i);
  RepairStats stats;
  TriangleAdjacency adj;
  orient_consistently(tube, stats, &adj);
  EXPECT_EQ(adj.opposite, build_adjacency(tube).opposite);
  EXPECT_EQ(tube.triangles, testing::open_tube(12, 4).triangles);
}

}  // namespace
}  // namespace vm
