// The cut across a vessel at a point (core/prepare/cut_across_vessel.h), on
// closed phantoms whose vessel axes and radii are known.
#include "core/prepare/cut_across_vessel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/phantom/vessel_phantom.h"
#include "tests/support/phantoms.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

struct Phantom {
  SurfaceMesh mesh;
  PhantomTruth truth;
  TriangleAdjacency adj;
};

Phantom closed_phantom(PhantomKind kind, double noise) {
  Phantom p;
  p.mesh = testing::phantom(kind, /*open_ends=*/false, 0.1, noise, &p.truth);
  p.adj = build_adjacency(p.mesh);
  return p;
}

/// A unit vector perpendicular to a.
Vec3 perpendicular(const Vec3& a) {
  const Vec3 other = std::abs(a[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  return normalized(cross(a, other));
}

TEST(CutAcrossVessel, PerpendicularToTheVesselThroughItsCentreFacingTheNearEnd) {
  // A closed straight tube of radius 1 along z from 0 to 8 (flat ends).
  const SurfaceMesh tube = testing::capped_tube(48, 64, 1.0, 8.0);
  const TriangleAdjacency adj = build_adjacency(tube);
  for (double z : {1.5, 3.0, 5.5}) {
    SCOPED_TRACE(z);
    for (const Vec3& side : {Vec3{1.3, 0, 0}, Vec3{0, -0.9, 0}, Vec3{0.6, 0.6, 0}}) {
      auto cut = cut_across_vessel(tube, adj, Vec3{0, 0, z} + side);
      ASSERT_TRUE(cut.ok()) << cut.message();
      const VesselCut& c = cut.value();
      // Toward the nearer end, along the axis within a degree.
      const Vec3 toward = z < 4 ? Vec3{0, 0, -1} : Vec3{0, 0, 1};
      EXPECT_GT(dot(c.plane.normal, toward), std::cos(std::numbers::pi / 180));
      EXPECT_NEAR(c.radius, 1.0, 0.01);
      // Through the axis, at the depth of the wall vertex nearest the click.
      EXPECT_LT(std::hypot(c.plane.point[0], c.plane.point[1]), 0.02);
      EXPECT_NEAR(c.plane.point[2], z, 8.0 / 64);
      EXPECT_GT(c.roundness, 0.95);
      // The side removed: the wall from the cut to the end and the end disk.
      const double h = z < 4 ? c.plane.point[2] : 8 - c.plane.point[2];
      EXPECT_NEAR(c.area_removed, 2 * std::numbers::pi * h + std::numbers::pi,
                  0.03 * c.area_removed);
    }
  }
}

TEST(CutAcrossVessel, ABranchOfTheBifurcationIsCutAcross) {
  const Phantom p = closed_phantom(PhantomKind::kBifurcation, 0.3);
  ASSERT_EQ(p.truth.end_tips.size(), 3u);
  for (size_t e = 0; e < 3; ++e) {
    SCOPED_TRACE(e);
    const Vec3 out = p.truth.end_directions[e];
    const double R = p.truth.end_radii[e];
    const Vec3 click = p.truth.end_tips[e] - (2.5 * R) * out + R * perpendicular(out);
    auto cut = cut_across_vessel(p.mesh, p.adj, click);
    ASSERT_TRUE(cut.ok()) << cut.message();
    EXPECT_GT(dot(cut.value().plane.normal, out), std::cos(5 * std::numbers::pi / 180));
    EXPECT_NEAR(cut.value().radius, R, 0.08 * R);
  }
}

TEST(CutAcrossVessel, NotOnAVesselsRoundedEnd) {
  const Phantom p = closed_phantom(PhantomKind::kBifurcation, 0);
  for (size_t e = 0; e < 3; ++e) {
    SCOPED_TRACE(e);
    const Vec3 out = p.truth.end_directions[e];
    const double R = p.truth.end_radii[e];
    for (double depth : {0.2, 0.6}) {
      const Vec3 click = p.truth.end_tips[e] - (depth * R) * out + R * perpendicular(out);
      auto cut = cut_across_vessel(p.mesh, p.adj, click);
      ASSERT_FALSE(cut.ok()) << depth << ": radius " << cut.value().radius;
      EXPECT_NE(cut.message().find("cannot cut across the vessel at ("), std::string::npos);
    }
  }
}

TEST(CutAcrossVessel, AnAneurysmDomeIsNoVessel) {
  const Phantom p = closed_phantom(PhantomKind::kAneurysm, 0);
  // The dome: the phantom's aneurysm is a bulb of radius 0.95 about
  // (0.15, 1.05, 1.6) on the side of the parent vessel (core/phantom); its
  // top, on the side away from the vessel, is clicked.
  const Vec3 dome{0.15, 1.05 + 0.95, 1.6};
  auto cut = cut_across_vessel(p.mesh, p.adj, dome);
  ASSERT_FALSE(cut.ok()) << point_text(dome) << " radius " << cut.value().radius << " normal "
                         << point_text(cut.value().plane.normal) << " at "
                         << point_text(cut.value().plane.point);
  EXPECT_NE(cut.message().find("cannot cut across the vessel at ("), std::string::npos)
      << cut.message();
  EXPECT_NE(cut.message().find("not a tube"), std::string::npos) << cut.message();
}

TEST(CutAcrossVessel, AnEmptySurfaceIsRefused) {
  SurfaceMesh empty;
  auto cut = cut_across_vessel(empty, build_adjacency(empty), {0, 0, 0});
  EXPECT_FALSE(cut.ok());
}

}  // namespace
}  // namespace vm
