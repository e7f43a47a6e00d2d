#include "core/phantom/vessel_phantom.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/mesh/topology.h"
#include "core/mesh/triangle_normals.h"
#include "tests/support/phantoms.h"

namespace vm {
namespace {

struct Case {
  PhantomKind kind;
  const char* name;
};

class PhantomKinds : public ::testing::TestWithParam<Case> {};

TEST_P(PhantomKinds, TopologyMatchesTheTruth) {
  PhantomOptions o;
  o.kind = GetParam().kind;
  o.voxel = 0.1;
  o.noise = 0.3;
  PhantomTruth truth;
  auto r = make_vessel_phantom(o, &truth);
  ASSERT_TRUE(r.ok()) << r.message();
  const SurfaceMesh& m = r.value();
  TopologyReport t = analyze_topology(m);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.nonmanifold_edges, 0u);
  EXPECT_EQ(t.nonmanifold_vertices, 0u);
  EXPECT_EQ(int(t.openings.size()), truth.openings);
  EXPECT_EQ(t.genus, truth.genus);
  // Each opening matches a cut of the model: same center and radius within
  // a voxel-sized staircase error.
  for (const Opening& op : t.openings) {
    double best = 1e9;
    size_t which = 0;
    for (size_t i = 0; i < truth.opening_centers.size(); ++i) {
      double d = 0;
      for (int k = 0; k < 3; ++k)
        d += (op.centroid[k] - truth.opening_centers[i][k]) *
             (op.centroid[k] - truth.opening_centers[i][k]);
      if (d < best) best = d, which = i;
    }
    EXPECT_LT(std::sqrt(best), 0.15);
    EXPECT_NEAR(op.radius, truth.opening_radii[which], 0.1 * truth.opening_radii[which]);
  }
  // Segmentation-like: plenty of triangles and some bad ones.
  EXPECT_GT(m.num_triangles(), 5000u);
}

INSTANTIATE_TEST_SUITE_P(All, PhantomKinds,
                         ::testing::Values(Case{PhantomKind::kTube, "tube"},
                                           Case{PhantomKind::kBifurcation, "bifurcation"},
                                           Case{PhantomKind::kAneurysm, "aneurysm"},
                                           Case{PhantomKind::kTorus, "torus"},
                                           Case{PhantomKind::kTree, "tree"},
                                           Case{PhantomKind::kRoot, "root"}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(Phantom, TreeHasElevenOpeningsOfMurrayRadii) {
  PhantomOptions o;
  o.kind = PhantomKind::kTree;
  o.voxel = 0.1;
  PhantomTruth truth;
  auto r = make_vessel_phantom(o, &truth);
  ASSERT_TRUE(r.ok()) << r.message();
  ASSERT_EQ(truth.openings, 11);
  // One inlet of radius ~0.97 (the trunk, cut near its start) and ten
  // outlets between the leaves' (3 Murray splits) and the side branches'.
  std::vector<double> radii = truth.opening_radii;
  std::sort(radii.begin(), radii.end());
  EXPECT_GT(radii.back(), 0.95);
  EXPECT_LT(radii[9], 0.55);
  EXPECT_GT(radii.front(), 0.25);
  EXPECT_EQ(analyze_topology(r.value()).genus, 0);
}

TEST(Phantom, ClosedEndsGiveAClosedSurface) {
  PhantomTruth truth;
  const SurfaceMesh m =
      testing::phantom(PhantomKind::kBifurcation, /*open_ends=*/false, 0.12, 0, &truth);
  ASSERT_GT(m.num_triangles(), 0u);
  TopologyReport t = analyze_topology(m);
  EXPECT_TRUE(t.closed);
  EXPECT_EQ(t.genus, 0);
  EXPECT_EQ(truth.openings, 0);
}

TEST(Phantom, RootIsShortWideAndTheWidestEnd) {
  PhantomTruth truth;
  const SurfaceMesh m = testing::phantom(PhantomKind::kRoot, /*open_ends=*/false, 0.15, 0, &truth);
  EXPECT_TRUE(analyze_topology(m).closed);
  ASSERT_EQ(truth.end_radii.size(), 5u);
  // The root (the first end) is the widest, 1.7 times the parent radius.
  EXPECT_NEAR(truth.end_radii[0], 1.7, 1e-9);
  for (size_t e = 1; e < 5; ++e) EXPECT_LT(truth.end_radii[e], 0.6 * truth.end_radii[0]);
}

TEST(Phantom, FanAndDomeCapsRiseBeyondTheCut) {
  // Each cap's highest point beyond its cut plane: 0.1 radius for a fan;
  // 0.3, 0.6 and 1 radius for the domes (in turn from end to end).
  for (PhantomCapShape shape : {PhantomCapShape::kFan, PhantomCapShape::kDome}) {
    SCOPED_TRACE(int(shape));
    PhantomTruth truth;
    const SurfaceMesh m = testing::capped_phantom(shape, 0.12, 0, &truth);
    const TopologyReport t = analyze_topology(m);
    EXPECT_TRUE(t.closed);
    EXPECT_EQ(t.genus, 0);
    EXPECT_EQ(t.nonmanifold_edges, 0u);
    ASSERT_EQ(truth.opening_centers.size(), 3u);
    std::vector<double> heights;
    for (size_t e = 0; e < 3; ++e) {
      const std::array<double, 3>& c = truth.opening_centers[e];
      const std::array<double, 3>& dir = truth.end_directions[e];
      const double R = truth.opening_radii[e];
      double top = -1e300;
      for (size_t v = 0; v < m.num_vertices(); ++v) {
        double along = 0, dist2 = 0;
        for (size_t k = 0; k < 3; ++k) {
          const double x = m.points[3 * v + k] - c[k];
          along += x * dir[k];
          dist2 += x * x;
        }
        if (dist2 - along * along < 1.2 * R * 1.2 * R && std::abs(along) < 2 * R)
          top = std::max(top, along);
      }
      heights.push_back(top / R);
    }
    std::sort(heights.begin(), heights.end());
    const std::vector<double> expected = shape == PhantomCapShape::kFan
                                             ? std::vector<double>{0.1, 0.1, 0.1}
                                             : std::vector<double>{0.3, 0.6, 1.0};
    for (size_t e = 0; e < 3; ++e) EXPECT_NEAR(heights[e], expected[e], 0.08) << e;
  }
}

TEST(Phantom, IsDeterministicAndSeedDependent) {
  PhantomOptions o;
  o.voxel = 0.15;
  o.noise = 0.4;
  auto a = make_vessel_phantom(o), b = make_vessel_phantom(o);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a.value().points, b.value().points);
  EXPECT_EQ(a.value().triangles, b.value().triangles);
  o.seed = 2;
  auto c = make_vessel_phantom(o);
  EXPECT_NE(a.value().points, c.value().points);
}

TEST(Phantom, ScaleScalesTheOutput) {
  PhantomOptions o;
  o.voxel = 0.15;
  auto a = make_vessel_phantom(o);
  o.scale = 10;
  PhantomTruth truth;
  auto b = make_vessel_phantom(o, &truth);
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_EQ(a.value().points.size(), b.value().points.size());
  EXPECT_NEAR(b.value().points[7], 10 * a.value().points[7], 1e-9);
  EXPECT_GT(truth.opening_radii[0], 5);
}

TEST(Phantom, RefusesBadOptions) {
  PhantomOptions o;
  o.voxel = 0;
  EXPECT_FALSE(make_vessel_phantom(o).ok());
  o.voxel = -1;
  EXPECT_FALSE(make_vessel_phantom(o).ok());
  o.voxel = 1e-4;
  auto r = make_vessel_phantom(o);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("too large"), std::string::npos) << r.message();
  o.voxel = 0.1;
  o.noise = -1;
  EXPECT_FALSE(make_vessel_phantom(o).ok());
}

}  // namespace
}  // namespace vm

namespace vm {
namespace {

TEST(Phantom, BinaryIsTheRawStaircaseOfTheMask) {
  PhantomOptions o;
  o.kind = PhantomKind::kBifurcation;
  o.voxel = 0.15;
  o.binary = true;
  PhantomTruth truth;
  auto r = make_vessel_phantom(o, &truth);
  ASSERT_TRUE(r.ok()) << r.message();
  const SurfaceMesh& m = r.value();
  const TopologyReport t = analyze_topology(m);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.nonmanifold_edges, 0u);
  EXPECT_EQ(t.genus, 0);
  EXPECT_EQ(int(t.openings.size()), truth.openings);
  // Every vertex but those of the end cuts in the middle of a grid edge:
  // its coordinates on the lattice of half voxels.
  const double half = 0.5 * o.voxel;
  size_t on_lattice = 0;
  for (size_t reference = 0; reference < 10; ++reference) {  // one of them not on a cut
    size_t on_this = 0;
    for (size_t v = 0; v < m.num_vertices(); ++v) {
      bool on = true;
      for (size_t k = 0; k < 3; ++k) {
        const double u = (m.points[3 * v + k] - m.points[3 * reference + k]) / half;
        on = on && std::fabs(u - std::round(u)) < 1e-6;
      }
      on_this += on;
    }
    on_lattice = std::max(on_lattice, on_this);
  }
  EXPECT_GT(double(on_lattice), 0.9 * double(m.num_vertices()));
  // Facets on the axes and their diagonals (the rest: marching cubes' fans
  // of non-planar sections), none oblique to them by a few degrees.
  double area = 0, on_grid = 0;
  for (size_t f = 0; f < m.num_triangles(); ++f) {
    const Vec3 n = triangle_cross(m, f);
    const double len = std::hypot(n[0], n[1], n[2]);
    area += len;
    // Sorted absolute components of a grid direction: (0,0,1), (0,1,1)/sqrt2, (1,1,1)/sqrt3.
    double s[3] = {std::fabs(n[0]) / len, std::fabs(n[1]) / len, std::fabs(n[2]) / len};
    std::sort(s, s + 3);
    const double r2 = 1 / std::sqrt(2.0), r3 = 1 / std::sqrt(3.0);
    const bool grid = std::hypot(s[0], s[1], s[2] - 1) < 1e-9 ||
                      std::hypot(s[0], s[1] - r2, s[2] - r2) < 1e-9 ||
                      std::hypot(s[0] - r3, s[1] - r3, s[2] - r3) < 1e-9;
    on_grid += grid ? len : 0;
  }
  EXPECT_GT(on_grid / area, 0.85);
  // Not the field's own surface.
  o.binary = false;
  auto field = make_vessel_phantom(o);
  ASSERT_TRUE(field.ok());
  EXPECT_NE(field.value().points, m.points);
}

}  // namespace
}  // namespace vm
