#include "core/surface/isotropic_remesh_patch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/geom/closest_point.h"
#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"
#include "core/mesh/topology.h"
#include "core/quality/triangle_quality.h"
#include "core/surface/resample_curve.h"
#include "tests/param/param_test_meshes.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

// The patch's boundary loop resampled at h, as the remesher's seams give it.
std::vector<PatchBoundaryPoint> boundary_at(const SurfaceMesh& m, double h) {
  const auto loops = boundary_loops(m, build_adjacency(m));
  EXPECT_EQ(loops.size(), 1u);
  const std::vector<int32_t>& loop = loops[0];
  std::vector<double> points, sizes;
  for (int32_t v : loop) {
    points.insert(points.end(), &m.points[3 * size_t(v)], &m.points[3 * size_t(v)] + 3);
    sizes.push_back(h);
  }
  std::vector<PatchBoundaryPoint> out;
  for (const CurveSample& s : resample_curve(points, sizes, true, 3))
    out.push_back({loop[s.segment], loop[(s.segment + 1) % loop.size()], s.t});
  return out;
}

Vec3 unit_normal(const SurfaceMesh& m, const int32_t* T) {
  const Vec3 n =
      cross(at(m.points, T[1]) - at(m.points, T[0]), at(m.points, T[2]) - at(m.points, T[0]));
  return (1 / norm(n)) * n;
}

// The contract of isotropic_remesh_patch on `in` with `boundary`: the
// boundary points first and exactly the boundary loop, a manifold disk,
// every vertex on its home triangle, triangles facing like the patch; and
// the edges near h with qualities above the floors given.
void check_patch(const SurfaceMesh& in, const std::vector<PatchBoundaryPoint>& boundary,
                 const PatchMesh& out, double h, double min_gamma, double mean_gamma,
                 const std::string& name) {
  SCOPED_TRACE(name);
  const SurfaceMesh& m = out.mesh;
  const size_t count = boundary.size();
  ASSERT_GE(m.num_vertices(), count);
  ASSERT_EQ(out.home.size(), m.num_vertices());
  for (size_t j = 0; j < count; ++j) {
    const PatchBoundaryPoint& b = boundary[j];
    const Vec3 x = (1 - b.t) * at(in.points, b.a) + b.t * at(in.points, b.b);
    EXPECT_LT(norm(at(m.points, int32_t(j)) - x), 1e-12) << "boundary point " << j;
  }
  const TriangleAdjacency adj = build_adjacency(m);
  size_t boundary_edges = 0;
  for (size_t he = 0; he < adj.opposite.size(); ++he)
    if (adj.opposite[he] == TriangleAdjacency::kBoundary) {
      ++boundary_edges;
      const int32_t a = half_edge_from(m, int32_t(he)), b = half_edge_to(m, int32_t(he));
      ASSERT_LT(size_t(a), count);
      EXPECT_EQ(size_t(b), (size_t(a) + 1) % count);
    }
  EXPECT_EQ(boundary_edges, count);
  const TopologyReport t = analyze_topology(m);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.openings.size(), 1u);
  EXPECT_EQ(t.genus, 0);
  EXPECT_EQ(t.nonmanifold_edges, 0u);
  EXPECT_EQ(t.nonmanifold_vertices, 0u);
  const double tol = 1e-9 * bounding_box(in.points).diagonal();
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    const int32_t home = out.home[v];
    ASSERT_TRUE(home >= 0 && size_t(home) < in.num_triangles());
    const int32_t* T = &in.triangles[3 * size_t(home)];
    double q[3];
    const double d2 =
        closest_point_on_triangle(&m.points[3 * v], &in.points[3 * size_t(T[0])],
                                  &in.points[3 * size_t(T[1])], &in.points[3 * size_t(T[2])], q);
    EXPECT_LE(std::sqrt(d2), tol) << "vertex " << v << " off its home triangle";
  }
  size_t facing_away = 0;
  for (size_t f = 0; f < m.num_triangles(); ++f) {
    const int32_t* T = &m.triangles[3 * f];
    const Vec3 n = unit_normal(m, T);
    const Vec3 nh = unit_normal(in, &in.triangles[3 * size_t(out.home[size_t(T[0])])]);
    if (dot(n, nh) < 0) ++facing_away;
  }
  EXPECT_EQ(facing_away, 0u);
  std::vector<double> lengths;
  std::set<std::pair<int32_t, int32_t>> seen;
  for (size_t f = 0; f < m.num_triangles(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto e = std::minmax(m.triangles[3 * f + k], m.triangles[3 * f + (k + 1) % 3]);
      if (seen.insert(e).second)
        lengths.push_back(norm(at(m.points, e.first) - at(m.points, e.second)));
    }
  EXPECT_NEAR(testing::median(lengths), h, 0.15 * h);
  const QualityStats q = quality_stats(triangle_qualities(m));
  EXPECT_GT(q.min, min_gamma);
  EXPECT_GT(q.mean, mean_gamma);
  std::cout << "[ info ] " << name << ": " << in.num_triangles() << " -> " << m.num_triangles()
            << " triangles, " << count << " boundary points, gamma min " << q.min << " mean "
            << q.mean << "\n";
}

// A spherical cap of the unit sphere (polar angle < 1 rad), `rings` rings.
SurfaceMesh cap(int rings, double jitter) {
  return testing::disk(rings, 6, jitter, [](double x, double y) {
    const double t = std::hypot(x, y), phi = std::atan2(y, x);
    return std::array<double, 3>{std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi),
                                 std::cos(t)};
  });
}

// Remeshes `in` at the uniform size h on its boundary resampled at h, and
// checks the result (check_patch); returns the fallback's counts.
IsotropicRemeshStats remesh_at(const SurfaceMesh& in, double h, double min_gamma, double mean_gamma,
                               const std::string& name) {
  const auto boundary = boundary_at(in, h);
  IsotropicRemeshStats stats;
  auto r =
      isotropic_remesh_patch(in, std::vector<double>(in.num_vertices(), h), boundary, {}, &stats);
  EXPECT_TRUE(r.ok()) << r.message();
  if (r.ok()) check_patch(in, boundary, r.value(), h, min_gamma, mean_gamma, name);
  return stats;
}

TEST(IsotropicRemeshPatch, CoarsensAFineCapOntoItsBoundaryPoints) {
  // Input edges about 0.035, asked 0.12: most boundary vertices are not
  // points and collapse away.
  const SurfaceMesh in = cap(30, 0.3);
  const IsotropicRemeshStats stats = remesh_at(in, 0.12, 0.5, 0.9, "fine cap");
  // Each boundary vertex that is not a point goes by one collapse.
  const size_t loop = boundary_loops(in, build_adjacency(in))[0].size();
  size_t at_vertices = 0;
  for (const PatchBoundaryPoint& b : boundary_at(in, 0.12)) at_vertices += b.t == 0;
  EXPECT_EQ(stats.boundary_collapses, loop - at_vertices);
  EXPECT_GT(stats.collapses, 0u);
}

TEST(IsotropicRemeshPatch, RefinesACoarseCap) {
  // Input edges about 0.2, asked 0.05: points inserted into the edges, the
  // inside split. The facets of a coarse cap bend sharply: vertices cannot
  // move across them, so the floors are lower.
  const SurfaceMesh in = cap(5, 0.3);
  const IsotropicRemeshStats stats = remesh_at(in, 0.05, 0.3, 0.85, "coarse cap");
  EXPECT_GT(stats.splits, in.num_triangles());
}

TEST(IsotropicRemeshPatch, CopesWithSliversAndANoisyPatch) {
  // A flat disk whose inside vertices are thrown about in height and along
  // the rings (slivers, steep folds of a few triangles), remeshed at a
  // size larger than its edges.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  SurfaceMesh in = testing::disk(12, 6, 0.45, [](double x, double y) {
    return std::array<double, 3>{x, y, 0.0};
  });
  const auto loops = boundary_loops(in, build_adjacency(in));
  std::vector<uint8_t> on_boundary(in.num_vertices(), 0);
  for (int32_t v : loops[0]) on_boundary[size_t(v)] = 1;
  for (size_t v = 0; v < in.num_vertices(); ++v)
    if (!on_boundary[v]) in.points[3 * v + 2] = 0.02 * u(rng);
  remesh_at(in, 0.2, 0.3, 0.85, "noisy disk");
}

TEST(IsotropicRemeshPatch, BoundaryPointsOffTheBoundaryAreRefused) {
  const SurfaceMesh in = cap(4, 0.2);
  std::vector<PatchBoundaryPoint> boundary = boundary_at(in, 0.2);
  ASSERT_GE(boundary.size(), 3u);
  // An interior vertex (0, the cap's pole) is not on the boundary.
  boundary[1] = {0, boundary[1].b, 0.5};
  auto r = isotropic_remesh_patch(in, std::vector<double>(in.num_vertices(), 0.2), boundary);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("boundary"), std::string::npos) << r.message();
  auto few = isotropic_remesh_patch(in, std::vector<double>(in.num_vertices(), 0.2),
                                    {boundary[0], boundary[2]});
  EXPECT_FALSE(few.ok());
}

}  // namespace
}  // namespace vm
