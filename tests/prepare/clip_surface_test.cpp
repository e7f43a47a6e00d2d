#include "core/prepare/clip_surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"
#include "core/mesh/enclosed_volume.h"
#include "core/mesh/topology.h"
#include "tests/support/expect_has.h"
#include "tests/support/phantoms.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

/// A closed capsule along z: a cylinder of radius r from z = 0 to z = len
/// (n around, m along) with hemispherical ends (k rings each), outward.
SurfaceMesh capsule(int n, int m, int k, double r, double len) {
  SurfaceMesh s;
  std::vector<double> zs, rs;
  for (int i = k; i >= 1; --i) {  // bottom hemisphere, from near the pole
    const double a = std::numbers::pi / 2 * i / k;
    zs.push_back(-r * std::sin(a)), rs.push_back(r * std::cos(a));
  }
  for (int j = 0; j <= m; ++j) zs.push_back(len * j / m), rs.push_back(r);
  for (int i = 1; i < k; ++i) {
    const double a = std::numbers::pi / 2 * i / k;
    zs.push_back(len + r * std::sin(a)), rs.push_back(r * std::cos(a));
  }
  const int rings = int(zs.size());
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * (i + 0.5 * (j % 2)) / n;
      s.points.insert(s.points.end(),
                      {rs[size_t(j)] * std::cos(a), rs[size_t(j)] * std::sin(a), zs[size_t(j)]});
    }
  for (int j = 0; j + 1 < rings; ++j)
    for (int i = 0; i < n; ++i) {
      const int32_t a = j * n + i, b = j * n + (i + 1) % n, c = a + n, d = b + n;
      if (j % 2 == 0)
        s.triangles.insert(s.triangles.end(), {a, b, c, b, d, c});
      else
        s.triangles.insert(s.triangles.end(), {a, b, d, a, d, c});
    }
  const int32_t bottom = int32_t(s.num_vertices()), top = bottom + 1;
  s.points.insert(s.points.end(), {0, 0, -r, 0, 0, len + r});
  for (int i = 0; i < n; ++i) {
    s.triangles.insert(s.triangles.end(), {(i + 1) % n, i, bottom});
    const int32_t last = (rings - 1) * n;
    s.triangles.insert(s.triangles.end(), {last + i, last + (i + 1) % n, top});
  }
  return s;
}

/// Every manifold edge is used once in each direction.
bool consistently_oriented(const SurfaceMesh& m) {
  const TriangleAdjacency adj = build_adjacency(m);
  for (size_t h = 0; h < adj.opposite.size(); ++h) {
    const int32_t o = adj.opposite[h];
    if (o == TriangleAdjacency::kNonManifold) return false;
    if (o >= 0 && half_edge_from(m, int32_t(h)) != half_edge_to(m, o)) return false;
  }
  return true;
}

/// The surface with each opening closed by a fan to its centroid (oriented
/// against the loop), for the enclosed volume.
SurfaceMesh closed_by_fans(SurfaceMesh m) {
  const TriangleAdjacency adj = build_adjacency(m);
  for (const std::vector<int32_t>& loop : boundary_loops(m, adj)) {
    double c[3] = {0, 0, 0};
    for (int32_t v : loop)
      for (int k = 0; k < 3; ++k) c[k] += m.points[3 * size_t(v) + size_t(k)] / double(loop.size());
    const int32_t centre = int32_t(m.num_vertices());
    m.points.insert(m.points.end(), c, c + 3);
    for (size_t i = 0; i < loop.size(); ++i)
      m.triangles.insert(m.triangles.end(), {loop[(i + 1) % loop.size()], loop[i], centre});
  }
  return m;
}

double triangle_area(const SurfaceMesh& m, size_t t) {
  const double* a = &m.points[3 * size_t(m.triangles[3 * t])];
  const double* b = &m.points[3 * size_t(m.triangles[3 * t + 1])];
  const double* c = &m.points[3 * size_t(m.triangles[3 * t + 2])];
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  return 0.5 * std::hypot(u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                          u[0] * w[1] - u[1] * w[0]);
}

/// Checks shared by every cut: manifold, one component, oriented, no
/// zero-area triangle, the openings' vertices on their planes.
void expect_clean_cut(const ClipResult& r, std::span<const ClipPlane> planes) {
  const TopologyReport t = analyze_topology(r.mesh);
  EXPECT_EQ(t.nonmanifold_edges, 0u);
  EXPECT_EQ(t.nonmanifold_vertices, 0u);
  EXPECT_EQ(t.components, 1);
  EXPECT_TRUE(consistently_oriented(r.mesh));
  for (size_t i = 0; i < r.mesh.num_triangles(); ++i) EXPECT_GT(triangle_area(r.mesh, i), 0);
  ASSERT_EQ(r.cut_of_vertex.size(), r.mesh.num_vertices());
  ASSERT_EQ(r.input_vertex.size(), r.mesh.num_vertices());
  // Each opening lies exactly on one plane, and its vertices say which.
  for (const Opening& op : t.openings) {
    const int32_t cut = r.cut_of_vertex[size_t(op.loop[0])];
    ASSERT_GE(cut, 0);
    const ClipPlane& p = planes[size_t(cut)];
    for (int32_t v : op.loop) {
      EXPECT_EQ(r.cut_of_vertex[size_t(v)], cut);
      double d = 0;
      for (int k = 0; k < 3; ++k)
        d += (r.mesh.points[3 * size_t(v) + size_t(k)] - p.point[size_t(k)]) * p.normal[size_t(k)];
      EXPECT_LT(std::abs(d), 1e-12) << "vertex " << v;
    }
  }
}

double polygon_area_factor(int n) { return n / 2.0 * std::sin(2 * std::numbers::pi / n); }

TEST(ClipSurface, CapsuleEndCutOpenWithTheRightVolume) {
  const int n = 64;
  const SurfaceMesh m = capsule(n, 40, 12, 1.0, 8.0);
  ASSERT_TRUE(analyze_topology(m).closed);
  const std::vector<ClipPlane> planes = {{{0, 0, 7.3}, {0, 0, 1}}};
  auto r = clip_surface(m, {}, planes);
  ASSERT_TRUE(r.ok()) << r.message();
  expect_clean_cut(r.value(), planes);
  const TopologyReport t = analyze_topology(r.value().mesh);
  ASSERT_EQ(t.openings.size(), 1u);
  EXPECT_NEAR(t.openings[0].centroid[2], 7.3, 1e-12);
  EXPECT_NEAR(t.openings[0].radius, 1.0, 0.01);
  ASSERT_EQ(r.value().cuts.size(), 1u);
  const ClipCut& c = r.value().cuts[0];
  EXPECT_NEAR(c.centroid[2], 7.3, 1e-12);
  EXPECT_NEAR(c.radius, t.openings[0].radius, 1e-9);
  // The area removed: the cylinder above 7.3 and the top hemisphere.
  EXPECT_NEAR(c.area_removed, 2 * std::numbers::pi * (0.7 + 1.0), 0.05);
  // The volume kept, with the opening closed: the cylinder below 7.3 and
  // the bottom hemisphere (polygons of n sides).
  const double want = polygon_area_factor(n) * 7.3 + 2.0 / 3 * std::numbers::pi;
  EXPECT_NEAR(enclosed_volume(closed_by_fans(r.value().mesh)), want, 0.01 * want);
}

TEST(ClipSurface, CappedTubeKeepsLabelsAndMarksTheCut) {
  const int n = 32, m = 16;
  const SurfaceMesh tube = testing::capped_tube(n, m, 1.0, 6.0);
  // Wall triangles: their band index along z; fans: 100 (bottom), 101 (top).
  std::vector<int32_t> labels;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < 2 * n; ++i) labels.push_back(j);
  for (int i = 0; i < n; ++i) labels.insert(labels.end(), {100, 101});
  ASSERT_EQ(labels.size(), tube.num_triangles());
  const std::vector<ClipPlane> planes = {{{0.1, 0.2, 5.1}, {0, 0, 1}}};
  auto r = clip_surface(tube, labels, planes);
  ASSERT_TRUE(r.ok()) << r.message();
  const ClipResult& c = r.value();
  expect_clean_cut(c, planes);
  ASSERT_EQ(c.labels.size(), c.mesh.num_triangles());
  const double band = 6.0 / m;
  size_t bottom = 0;
  for (size_t t = 0; t < c.mesh.num_triangles(); ++t) {
    const int32_t l = c.labels[t];
    EXPECT_NE(l, 101);  // the top cap is gone
    if (l == 100) {
      ++bottom;
      continue;
    }
    double z = 0;
    for (int k = 0; k < 3; ++k)
      z += c.mesh.points[3 * size_t(c.mesh.triangles[3 * t + size_t(k)]) + 2] / 3;
    EXPECT_GE(z, l * band - 1e-12);
    EXPECT_LE(z, (l + 1) * band + 1e-12);
    EXPECT_LE(z, 5.1);
  }
  EXPECT_EQ(bottom, size_t(n));
  // The loop is made of new vertices (no ring is near the plane); the
  // input vertices kept did not move.
  size_t fresh = 0, cut = 0;
  for (size_t v = 0; v < c.mesh.num_vertices(); ++v) {
    fresh += c.input_vertex[v] < 0;
    cut += c.cut_of_vertex[v] == 0;
    if (c.input_vertex[v] < 0) continue;
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(c.mesh.points[3 * v + size_t(k)],
                tube.points[3 * size_t(c.input_vertex[v]) + size_t(k)]);
  }
  EXPECT_EQ(fresh, cut);
  EXPECT_GE(cut, size_t(n));
  const double want = polygon_area_factor(n) * 5.1;
  EXPECT_NEAR(enclosed_volume(closed_by_fans(c.mesh)), want, 1e-9 * want);
}

TEST(ClipSurface, APlaneThroughARingOrNearItUsesItsVertices) {
  const int n = 32, m = 16;
  const SurfaceMesh tube = testing::capped_tube(n, m, 1.0, 6.0);
  // Ring 12 lies at z = 4.5: exactly on the plane, or moved onto it.
  for (double z : {4.5, 4.5 + 1e-4, 4.5 - 1e-4}) {
    const std::vector<ClipPlane> planes = {{{0, 0, z}, {0, 0, 1}}};
    auto r = clip_surface(tube, {}, planes);
    ASSERT_TRUE(r.ok()) << r.message();
    expect_clean_cut(r.value(), planes);
    size_t fresh = 0, cut = 0;
    for (size_t v = 0; v < r.value().mesh.num_vertices(); ++v) {
      fresh += r.value().input_vertex[v] < 0;
      cut += r.value().cut_of_vertex[v] == 0;
    }
    EXPECT_EQ(fresh, 0u) << z;
    EXPECT_EQ(cut, size_t(n)) << z;
    EXPECT_EQ(r.value().mesh.num_triangles(), tube.num_triangles() - 2 * n * 4 - n) << z;
  }
}

TEST(ClipSurface, AnObliquePlaneLeavesAPlanarLoop) {
  const SurfaceMesh m = capsule(48, 30, 10, 1.0, 8.0);
  const double s = 1 / std::sqrt(1 + 0.3 * 0.3);
  const std::vector<ClipPlane> planes = {{{0, 0, 6}, {0, 0.3 * s, s}}, {{0, 0, 1.5}, {0, 0, -1}}};
  auto r = clip_surface(m, {}, planes);
  ASSERT_TRUE(r.ok()) << r.message();
  expect_clean_cut(r.value(), planes);
  const TopologyReport t = analyze_topology(r.value().mesh);
  EXPECT_EQ(t.openings.size(), 2u);
  EXPECT_EQ(t.genus, 0);
  // An ellipse of semi-axes 1 and 1 / cos(tilt): area pi / s.
  EXPECT_NEAR(r.value().cuts[0].radius, std::sqrt(1 / s), 0.01);
}

// The message of clip_surface's refusal of `planes` on `m` (a test failure
// if it clips).
std::string clip_error(const SurfaceMesh& m, const std::vector<ClipPlane>& planes) {
  auto r = clip_surface(m, {}, planes);
  EXPECT_FALSE(r.ok());
  return r.message();
}

TEST(ClipSurface, APlaneFarFromTheSurfaceIsRefusedWithItsPoint) {
  const SurfaceMesh tube = testing::capped_tube(32, 16, 1.0, 6.0);
  // The plane z = 3 cuts the tube, but 50 away from the point given.
  const std::vector<ClipPlane> far = {{{50, 0, 3}, {0, 0, 1}}};
  const std::string error = clip_error(tube, far);
  EXPECT_HAS(error, "the plane at (50, 0, 3) does not cut the surface within");
  EXPECT_HAS(error, "{clip_plane}");
  // A plane that misses the surface altogether.
  const std::vector<ClipPlane> miss = {{{0, 0, 40}, {0, 0, 1}}};
  EXPECT_HAS(clip_error(tube, miss), "the plane at (0, 0, 40) with normal (0, 0, 1) does not cut");
}

TEST(ClipSurface, RefusesToRemoveMostOfTheSurface) {
  const SurfaceMesh tube = testing::capped_tube(32, 16, 1.0, 6.0);
  const std::vector<ClipPlane> planes = {{{0, 0, 1}, {0, 0, 1}}};
  const std::string error = clip_error(tube, planes);
  EXPECT_HAS(error, "the plane at (0, 0, 1) would remove 7");
  EXPECT_HAS(error, "% of the surface (the side its normal (0, 0, 1) points to)");
  // Turned around, it removes the short end.
  const std::vector<ClipPlane> turned = {{{0, 0, 1}, {0, 0, -1}}};
  EXPECT_TRUE(clip_surface(tube, {}, turned).ok());
}

TEST(ClipSurface, ACutThatDoesNotSeparateOrRunsIntoAnOpeningIsRefused) {
  const SurfaceMesh ring = testing::torus(48, 24, 3.0, 1.0);
  const std::vector<ClipPlane> across = {{{3, 0, 0}, {0, 1, 0}}};
  EXPECT_HAS(clip_error(ring, across), "does not divide the surface in two");
  const SurfaceMesh open = testing::open_tube(32, 16, 1.0, 4.0);
  const std::vector<ClipPlane> oblique = {{{0, 0, 0.2}, {0.98058, 0, 0.19612}}};
  EXPECT_HAS(clip_error(open, oblique), "runs into an opening of the surface near");
}

TEST(ClipSurface, APlaneAcrossTwoBranchesCutsOnlyTheOneAtItsPoint) {
  PhantomTruth truth;
  const SurfaceMesh m =
      testing::phantom(PhantomKind::kBifurcation, /*open_ends=*/false, 0.1, 0, &truth);
  ASSERT_GT(m.num_triangles(), 0u);
  auto top_z = [](const SurfaceMesh& s, bool right) {
    double z = -1e300;
    for (size_t v = 0; v < s.num_vertices(); ++v)
      if ((s.points[3 * v] > 0) == right) z = std::max(z, s.points[3 * v + 2]);
    return z;
  };
  // z = 5 crosses both daughter branches; the point is in the right one.
  const std::vector<ClipPlane> planes = {{{2.85, 0.25, 5.0}, {0, 0, 1}}};
  auto r = clip_surface(m, {}, planes);
  ASSERT_TRUE(r.ok()) << r.message();
  expect_clean_cut(r.value(), planes);
  const TopologyReport t = analyze_topology(r.value().mesh);
  ASSERT_EQ(t.openings.size(), 1u);
  EXPECT_GT(t.openings[0].centroid[0], 2);
  EXPECT_NEAR(top_z(r.value().mesh, true), 5.0, 1e-12);
  EXPECT_EQ(top_z(r.value().mesh, false), top_z(m, false));  // the left branch is whole
  EXPECT_EQ(r.value().components_dropped, 0);
}

TEST(ClipSurface, EachPlaneMarksItsOwnOpening) {
  const SurfaceMesh tube = testing::capped_tube(24, 12, 1.0, 6.0);
  const std::vector<ClipPlane> planes = {{{0, 0, 5.2}, {0, 0, 1}}, {{0, 0, 0.7}, {0, 0, -1}}};
  auto r = clip_surface(tube, {}, planes);
  ASSERT_TRUE(r.ok()) << r.message();
  expect_clean_cut(r.value(), planes);
  const TopologyReport t = analyze_topology(r.value().mesh);
  ASSERT_EQ(t.openings.size(), 2u);
  EXPECT_EQ(t.genus, 0);
  ASSERT_EQ(r.value().cuts.size(), 2u);
  EXPECT_NEAR(r.value().cuts[0].centroid[2], 5.2, 1e-12);
  EXPECT_NEAR(r.value().cuts[1].centroid[2], 0.7, 1e-12);
}

}  // namespace
}  // namespace vm
