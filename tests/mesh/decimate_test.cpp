#include "core/mesh/decimate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/geom/vec3.h"
#include "core/mesh/surface_distance.h"
#include "core/mesh/topology.h"
#include "core/quality/triangle_quality.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

struct Limits {
  std::vector<double> error, edge;
  DecimateLimits limits() const { return {.max_error = error, .max_edge = edge}; }
};

Limits uniform(const SurfaceMesh& m, double error, double edge) {
  return {std::vector<double>(m.num_vertices(), error),
          std::vector<double>(m.num_vertices(), edge)};
}

double longest_edge(const SurfaceMesh& m) {
  double longest = 0;
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (size_t k = 0; k < 3; ++k)
      longest = std::max(longest, norm(at(m.points, m.triangles[3 * t + k]) -
                                       at(m.points, m.triangles[3 * t + (k + 1) % 3])));
  return longest;
}

/// Every output vertex is the input vertex it names, in increasing order.
void expect_vertex_subset(const SurfaceMesh& in, const DecimatedSurface& out) {
  ASSERT_EQ(out.input_vertex.size(), out.mesh.num_vertices());
  for (size_t v = 0; v < out.input_vertex.size(); ++v) {
    if (v > 0) {
      EXPECT_LT(out.input_vertex[v - 1], out.input_vertex[v]);
    }
    EXPECT_EQ(at(out.mesh.points, int32_t(v)), at(in.points, out.input_vertex[v]));
  }
}

void expect_same_topology(const SurfaceMesh& in, const SurfaceMesh& out) {
  const TopologyReport a = analyze_topology(in), b = analyze_topology(out);
  EXPECT_EQ(b.genus, a.genus);
  EXPECT_EQ(b.components, a.components);
  EXPECT_EQ(b.openings.size(), a.openings.size());
  EXPECT_EQ(b.nonmanifold_edges, 0u);
  EXPECT_EQ(b.nonmanifold_vertices, 0u);
  EXPECT_EQ(b.triangles + 2 * (a.vertices - b.vertices), a.triangles);
}

TEST(Decimate, AFineTubeKeepsItsRimsShapeAndTopologyWithinTheLimits) {
  const SurfaceMesh tube = testing::open_tube(256, 200, 1.0, 4.0);  // edges about 0.02
  const Limits l = uniform(tube, 0.002, 0.2);
  const DecimatedSurface out = decimate_surface(tube, l.limits());
  expect_vertex_subset(tube, out);
  expect_same_topology(tube, out.mesh);
  EXPECT_LT(out.mesh.num_triangles(), tube.num_triangles() / 10);
  // The rims' 512 vertices are all kept, so both openings keep their loops.
  const TopologyReport t = analyze_topology(out.mesh);
  ASSERT_EQ(t.openings.size(), 2u);
  for (const Opening& o : t.openings) EXPECT_EQ(o.loop.size(), 256u);
  // New edges stay within the limit, triangles face outward and are well shaped.
  EXPECT_LE(longest_edge(out.mesh), 0.2 + 1e-12);
  for (size_t f = 0; f < out.mesh.num_triangles(); ++f) {
    const int32_t* c = &out.mesh.triangles[3 * f];
    const Vec3 a = at(out.mesh.points, c[0]), b = at(out.mesh.points, c[1]),
               d = at(out.mesh.points, c[2]);
    const Vec3 centre = (1.0 / 3) * (a + b + d);
    EXPECT_GT(dot(cross(b - a, d - a), Vec3{centre[0], centre[1], 0}), 0) << "triangle " << f;
    EXPECT_GE(triangle_gamma(a.data(), b.data(), d.data()), 0.25) << "triangle " << f;
  }
  // The input stays near the output: chords of 0.2 on a radius 1 sag 0.005.
  EXPECT_LT(distances_to_surface(out.mesh, tube.points).max, 0.006);
}

TEST(Decimate, AFlatGridCollapsesToTheEdgeLimitWithoutError) {
  const SurfaceMesh grid = testing::square_grid(100);
  const Limits l = uniform(grid, 1e-9, 0.1);
  const DecimatedSurface out = decimate_surface(grid, l.limits());
  expect_vertex_subset(grid, out);
  expect_same_topology(grid, out.mesh);
  EXPECT_LT(out.mesh.num_triangles(), grid.num_triangles() / 10);
  for (size_t v = 0; v < out.mesh.num_vertices(); ++v) EXPECT_EQ(out.mesh.points[3 * v + 2], 0.0);
  EXPECT_LE(longest_edge(out.mesh), 0.1 + 1e-12);
}

TEST(Decimate, TheErrorLimitKeepsACurvedSurfaceFine) {
  const SurfaceMesh tube = testing::open_tube(256, 200, 1.0, 4.0);
  const DecimatedSurface loose = decimate_surface(tube, uniform(tube, 0.002, 0.5).limits());
  const DecimatedSurface tight = decimate_surface(tube, uniform(tube, 1e-5, 0.5).limits());
  EXPECT_GT(tight.mesh.num_triangles(), 2 * loose.mesh.num_triangles());
  EXPECT_LT(distances_to_surface(tight.mesh, tube.points).max, 1e-4);
}

TEST(Decimate, ATorusKeepsItsGenusAndTheResultIsDeterministic) {
  const SurfaceMesh torus = testing::torus(200, 80);
  const Limits l = uniform(torus, 0.01, 0.6);
  const DecimatedSurface a = decimate_surface(torus, l.limits());
  const DecimatedSurface b = decimate_surface(torus, l.limits());
  expect_same_topology(torus, a.mesh);
  EXPECT_EQ(analyze_topology(a.mesh).genus, 1);
  EXPECT_LT(a.mesh.num_triangles(), torus.num_triangles() / 4);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(a.input_vertex, b.input_vertex);
}

TEST(Decimate, ZeroLimitsChangeNothing) {
  const SurfaceMesh tube = testing::open_tube(32, 10);
  const DecimatedSurface out = decimate_surface(tube, uniform(tube, 0, 0).limits());
  EXPECT_EQ(out.mesh.points, tube.points);
  EXPECT_EQ(out.mesh.triangles, tube.triangles);
}

}  // namespace
}  // namespace vm
