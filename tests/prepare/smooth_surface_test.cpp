#include "core/prepare/smooth_surface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"
#include "core/mesh/enclosed_volume.h"
#include "core/mesh/topology.h"
#include "core/mesh/marching_cubes.h"
#include "core/phantom/vessel_phantom.h"
#include "core/pipeline/option_values.h"
#include "core/prepare/recognize_caps.h"
#include "tests/support/icosphere.h"
#include "tests/support/phantoms.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

/// The raw staircase of a binary voxel mask of the phantom.
SurfaceMesh binary_phantom(PhantomKind kind, double voxel, bool open_ends = true,
                           bool flat_caps = false) {
  PhantomOptions o;
  o.kind = kind;
  o.voxel = voxel;
  o.binary = true;
  o.open_ends = open_ends;
  o.flat_caps = flat_caps;
  return testing::phantom(o);
}

/// Marching cubes on the binary mask of a ball of radius r (voxel h).
SurfaceMesh binary_ball(double r, double h) {
  GridSpec g;
  g.spacing = h;
  const int n = int(std::ceil(2 * r / h)) + 6;
  g.nx = g.ny = g.nz = n;
  for (double& o : g.origin) o = -0.5 * h * (n - 1) + 0.1 * h;  // off-center grid
  return marching_cubes(g, [&](int k, float* plane) {
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = g.origin[0] + h * i, y = g.origin[1] + h * j, z = g.origin[2] + h * k;
        plane[i + n * j] = x * x + y * y + z * z < r * r ? -1.0f : 1.0f;
      }
  });
}

SmoothOptions half_voxel(double voxel, int passes) {
  SmoothOptions o;
  o.passes = passes;
  o.max_displacement = {0.5 * voxel, 0.5 * voxel, 0.5 * voxel};
  return o;
}

std::array<double, 3> unit_normal(const SurfaceMesh& m, size_t t) {
  const double* a = &m.points[3 * size_t(m.triangles[3 * t])];
  const double* b = &m.points[3 * size_t(m.triangles[3 * t + 1])];
  const double* c = &m.points[3 * size_t(m.triangles[3 * t + 2])];
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  std::array<double, 3> n = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                             u[0] * w[1] - u[1] * w[0]};
  const double len = std::hypot(n[0], n[1], n[2]);
  for (double& x : n) x /= len;
  return n;
}

/// Share of the interior edges whose triangles' normals differ by more than
/// `degrees`.
double crease_share(const SurfaceMesh& m, double degrees) {
  const TriangleAdjacency adj = build_adjacency(m);
  const double limit = std::cos(degrees * std::numbers::pi / 180);
  size_t edges = 0, creases = 0;
  for (size_t h = 0; h < adj.opposite.size(); ++h) {
    const int32_t o = adj.opposite[h];
    if (o < 0 || size_t(o) < h) continue;
    const auto a = unit_normal(m, h / 3), b = unit_normal(m, size_t(o) / 3);
    ++edges;
    creases += a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < limit;
  }
  return double(creases) / double(edges);
}

TEST(ParseSmoothing, AutoOffOrPasses) {
  EXPECT_EQ(parse_smoothing("auto")->mode, Smoothing::Mode::kAuto);
  EXPECT_EQ(parse_smoothing("off")->mode, Smoothing::Mode::kOff);
  auto n = parse_smoothing("12");
  ASSERT_TRUE(n);
  EXPECT_EQ(n->mode, Smoothing::Mode::kPasses);
  EXPECT_EQ(n->passes, 12);
  for (const char* bad : {"0", "-3", "1001", "x", "", "2.5", "10 "})
    EXPECT_FALSE(parse_smoothing(bad)) << bad;
}

struct Kind {
  PhantomKind kind;
  const char* name;
};

class BinaryPhantoms : public ::testing::TestWithParam<Kind> {};

TEST_P(BinaryPhantoms, AreStaircasesWithTheirVoxel) {
  for (double voxel : {0.12, 0.16}) {
    const SurfaceMesh m = binary_phantom(GetParam().kind, voxel);
    const StaircaseReport r = detect_staircase(m);
    EXPECT_TRUE(r.staircase) << voxel;
    EXPECT_NEAR(r.voxel, voxel, 1e-6 * voxel);
    for (double s : r.spacing) EXPECT_NEAR(s, voxel, 1e-6 * voxel);
    EXPECT_GT(r.direction_fraction, 0.85);  // the rest: fans of non-planar cube sections
    EXPECT_GT(r.lattice_fraction, 0.9);     // the rest: vertices of the end cuts
    EXPECT_GT(r.terraces, 20);
  }
}

TEST_P(BinaryPhantoms, SmoothFieldsAndNoiseAreNotStaircases) {
  for (double noise : {0.0, 0.3}) {
    const SurfaceMesh m = testing::phantom(GetParam().kind, true, 0.12, noise);
    const StaircaseReport r = detect_staircase(m);
    EXPECT_FALSE(r.staircase) << noise;
    EXPECT_LT(r.direction_fraction, 0.3);
    EXPECT_LT(r.lattice_fraction, 0.2);
    EXPECT_EQ(r.voxel, 0);
  }
}

INSTANTIATE_TEST_SUITE_P(All, BinaryPhantoms,
                         ::testing::Values(Kind{PhantomKind::kTube, "tube"},
                                           Kind{PhantomKind::kBifurcation, "bifurcation"},
                                           Kind{PhantomKind::kAneurysm, "aneurysm"}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(DetectStaircase, AnalyticSurfacesAreNot) {
  for (const SurfaceMesh& m :
       {testing::open_tube(32, 16), testing::capped_tube(24, 8, 2.0, 5.0), testing::torus(48, 24),
        testing::icosphere(4), testing::square_grid(8), SurfaceMesh{}}) {
    const StaircaseReport r = detect_staircase(m);
    EXPECT_FALSE(r.staircase) << m.num_triangles() << " triangles";
    EXPECT_EQ(r.voxel, 0);
  }
}

TEST(DetectStaircase, MeasuresEachSideOfAnAnisotropicVoxel) {
  // Stretching a binary staircase along z is the staircase of a grid with
  // voxels 1.5 times as tall.
  SurfaceMesh m = binary_phantom(PhantomKind::kBifurcation, 0.12);
  for (size_t v = 0; v < m.num_vertices(); ++v) m.points[3 * v + 2] *= 1.5;
  const StaircaseReport r = detect_staircase(m);
  EXPECT_TRUE(r.staircase);
  EXPECT_NEAR(r.spacing[0], 0.12, 1e-6);
  EXPECT_NEAR(r.spacing[1], 0.12, 1e-6);
  EXPECT_NEAR(r.spacing[2], 0.18, 1e-6);
  EXPECT_NEAR(r.voxel, 0.18, 1e-6);
  EXPECT_GT(r.direction_fraction, 0.85);  // the diagonals of a tall voxel
}

TEST(DetectStaircase, VoxelCornersGiveTheVoxelNotHalfOfIt) {
  // Voxel faces (a cuberille: every vertex a voxel corner) of a ball.
  const double h = 0.1, r = 1.0;
  const int n = 26;
  auto inside = [&](int i, int j, int k) {
    const double x = h * (i - n / 2 + 0.5), y = h * (j - n / 2 + 0.5), z = h * (k - n / 2 + 0.5);
    return i >= 0 && j >= 0 && k >= 0 && i < n && j < n && k < n && x * x + y * y + z * z < r * r;
  };
  SurfaceMesh m;
  auto corner = [&](int i, int j, int k) {
    m.points.insert(m.points.end(), {h * (i - n / 2), h * (j - n / 2), h * (k - n / 2)});
    return int32_t(m.num_vertices() - 1);
  };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (!inside(i, j, k)) continue;
        for (int axis = 0; axis < 3; ++axis)
          for (int side = 0; side < 2; ++side) {
            int d[3] = {0, 0, 0};
            d[axis] = side ? 1 : -1;
            if (inside(i + d[0], j + d[1], k + d[2])) continue;
            // The face's corners (unwelded: detection needs no topology).
            const int u = (axis + 1) % 3, w = (axis + 2) % 3;
            int c[4][3];
            for (int q = 0; q < 4; ++q) {
              c[q][0] = i, c[q][1] = j, c[q][2] = k;
              c[q][axis] += side;
              c[q][u] += q == 1 || q == 2;
              c[q][w] += q >= 2;
            }
            int32_t ids[4];
            for (int q = 0; q < 4; ++q) ids[q] = corner(c[q][0], c[q][1], c[q][2]);
            m.triangles.insert(m.triangles.end(), {ids[0], ids[1], ids[2], ids[0], ids[2], ids[3]});
          }
      }
  const StaircaseReport s = detect_staircase(m);
  EXPECT_TRUE(s.staircase);
  EXPECT_NEAR(s.voxel, h, 1e-9);
  EXPECT_GT(s.direction_fraction, 0.99);
}

TEST(SmoothSurface, KeepsEveryVertexWithinHalfAVoxelAndMovesNoTriangle) {
  const double voxel = 0.12;
  const SurfaceMesh input = binary_phantom(PhantomKind::kAneurysm, voxel);
  SurfaceMesh m = input;
  const SmoothReport r = smooth_surface(m, build_adjacency(m), half_voxel(voxel, 25));
  EXPECT_EQ(r.passes, 25);
  EXPECT_EQ(m.triangles, input.triangles);
  ASSERT_EQ(m.points.size(), input.points.size());
  double worst = 0;
  for (size_t v = 0; v < m.num_vertices(); ++v)
    worst = std::max(worst, std::hypot(m.points[3 * v] - input.points[3 * v],
                                       m.points[3 * v + 1] - input.points[3 * v + 1],
                                       m.points[3 * v + 2] - input.points[3 * v + 2]));
  EXPECT_LE(worst, 0.5 * voxel * (1 + 1e-12));
  EXPECT_NEAR(r.max_displacement, worst, 1e-15);
  EXPECT_GT(worst, 0.3 * voxel);  // it did move
  EXPECT_LE(r.max_displacement_ratio, 1 + 1e-12);
  // Still the same surface: one component, the same openings, no triangle
  // turned over.
  const TopologyReport t = analyze_topology(m);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.openings.size(), 3u);
  size_t flipped = 0;
  for (size_t f = 0; f < m.num_triangles(); ++f) {
    const auto a = unit_normal(m, f), b = unit_normal(input, f);
    flipped += a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < 0;
  }
  EXPECT_EQ(flipped, 0u);
}

TEST(SmoothSurface, RemovesTheSteps) {
  for (PhantomKind kind : {PhantomKind::kTube, PhantomKind::kBifurcation}) {
    const double voxel = 0.12;
    SurfaceMesh m = binary_phantom(kind, voxel);
    // The staircase: a quarter of the edges are creases of 45 to 90 degrees.
    EXPECT_GT(crease_share(m, 30), 0.2);
    EXPECT_GT(crease_share(m, 60), 0.0);
    smooth_surface(m, build_adjacency(m), half_voxel(voxel, staircase_passes(m, voxel)));
    EXPECT_LT(crease_share(m, 30), 0.003);
    EXPECT_EQ(crease_share(m, 60), 0.0);  // nothing for sharp-feature detection
    EXPECT_FALSE(detect_staircase(m).staircase);
  }
}

TEST(SmoothSurface, KeepsOpeningsInTheirPlanesAndInPlace) {
  const double voxel = 0.16;
  const SurfaceMesh input = binary_phantom(PhantomKind::kBifurcation, voxel);
  SurfaceMesh m = input;
  const TriangleAdjacency adj = build_adjacency(m);
  const SmoothReport r = smooth_surface(m, adj, half_voxel(voxel, 25));
  const TopologyReport before = analyze_topology(input, adj), after = analyze_topology(m, adj);
  ASSERT_EQ(before.openings.size(), 3u);
  ASSERT_EQ(after.openings.size(), 3u);
  EXPECT_GE(r.held_vertices, before.boundary_edges);
  EXPECT_EQ(r.fixed_vertices, 0u);
  for (size_t i = 0; i < 3; ++i) {
    const Opening &a = before.openings[i], &b = after.openings[i];
    ASSERT_EQ(a.loop, b.loop);
    // Every rim vertex stays in the plane of the cut ...
    for (int32_t v : a.loop) {
      double d = 0;
      for (int k = 0; k < 3; ++k) d += (m.points[3 * size_t(v) + k] - a.centroid[k]) * a.normal[k];
      EXPECT_LT(std::fabs(d), 1e-9);
    }
    // ... and the opening where it was, of the same size.
    EXPECT_LT(std::hypot(b.centroid[0] - a.centroid[0], b.centroid[1] - a.centroid[1],
                         b.centroid[2] - a.centroid[2]),
              0.05 * voxel);
    EXPECT_NEAR(b.radius, a.radius, 0.02 * a.radius);
    EXPECT_GT(b.normal[0] * a.normal[0] + b.normal[1] * a.normal[1] + b.normal[2] * a.normal[2],
              1 - 1e-9);
  }
}

TEST(SmoothSurface, DoesNotShrink) {
  // A closed staircase keeps the volume of the ball it was made from.
  const double radius = 1.0, voxel = 0.1;
  SurfaceMesh ball = binary_ball(radius, voxel);
  const double exact = 4.0 / 3.0 * std::numbers::pi * std::pow(radius, 3);
  EXPECT_NEAR(enclosed_volume(ball) / exact, 1, 0.02);
  const SmoothReport r =
      smooth_surface(ball, build_adjacency(ball), half_voxel(voxel, staircase_passes(ball, voxel)));
  EXPECT_NEAR(enclosed_volume(ball) / exact, 1, 0.02);
  EXPECT_NEAR(r.volume_after / r.volume_before, 1, 1e-6);
  // Without the volume constraint, Taubin's filter alone shrinks a little
  // less than plain Laplacian smoothing; with it the volume is exact.
  SurfaceMesh open = binary_phantom(PhantomKind::kTube, 0.12);
  const SmoothReport o = smooth_surface(open, build_adjacency(open), half_voxel(0.12, 25));
  EXPECT_NEAR(o.volume_after / o.volume_before, 1, 1e-6);
  EXPECT_GT(o.volume_before, 0);
}

TEST(SmoothSurface, KeepsFlatCapsFlatAndRecognisable) {
  const double voxel = 0.12;
  SurfaceMesh m = binary_phantom(PhantomKind::kBifurcation, voxel, true, true);
  const TriangleAdjacency adj = build_adjacency(m);
  SmoothOptions o = half_voxel(voxel, 25);
  o.flat_min_area = 16 * voxel * voxel;
  o.grid = {voxel, voxel, voxel};
  const SurfaceMesh input = m;
  const SmoothReport r = smooth_surface(m, adj, o);
  EXPECT_EQ(r.flat_regions, 3u);
  const CapRecognition caps = recognize_caps(m, adj, {}, {});
  ASSERT_EQ(caps.caps.size(), 3u);
  for (const RecognizedCap& cap : caps.caps) {
    // Every vertex of the cap on the plane it had.
    const int32_t first = input.triangles[3 * size_t(cap.triangles[0])];
    for (int32_t t : cap.triangles)
      for (int c = 0; c < 3; ++c) {
        const size_t v = size_t(m.triangles[3 * size_t(t) + size_t(c)]);
        double d = 0;
        for (int k = 0; k < 3; ++k)
          d += (m.points[3 * v + k] - input.points[3 * size_t(first) + k]) * cap.normal[k];
        EXPECT_LT(std::fabs(d), 1e-9);
      }
  }
  // Without holding them, the rims round off and the caps are lost.
  SurfaceMesh rounded = input;
  smooth_surface(rounded, adj, half_voxel(voxel, 25));
  EXPECT_LT(recognize_caps(rounded, adj, {}, {}).caps.size(), 3u);
}

TEST(SmoothSurface, ThePassesReachTwoVoxels) {
  const SurfaceMesh m = binary_phantom(PhantomKind::kTube, 0.16);
  const int passes = staircase_passes(m, 0.16);
  EXPECT_GE(passes, 24);  // marching cubes' median edge is about a voxel
  EXPECT_LE(passes, 26);
  EXPECT_EQ(staircase_passes(m, 100.0), 200);
  EXPECT_EQ(staircase_passes(m, 0.001), 10);
  EXPECT_EQ(staircase_passes(SurfaceMesh{}, 0.1), 10);
  EXPECT_NEAR(median_edge_length(testing::square_grid(4)), 0.25, 1e-12);
}

}  // namespace
}  // namespace vm
