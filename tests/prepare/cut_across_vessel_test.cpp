// The cut across a vessel at a point (core/prepare/cut_across_vessel.h), on
// closed phantoms whose vessel axes and radii are known.
#include "core/prepare/cut_across_vessel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/phantom/vessel_phantom.h"
#include "core/prepare/vessel_ends.h"
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

TEST(CutAcrossVessel, OnAVesselsRoundedEndTheEndsCut) {
  // Where the vessel is no tube (its rounded end), a click gives the cut
  // that clip auto makes at that end.
  const Phantom p = closed_phantom(PhantomKind::kBifurcation, 0);
  const VesselEnds ends = find_vessel_ends(p.mesh);
  ASSERT_EQ(ends.ends.size(), 3u);
  for (size_t e = 0; e < 3; ++e) {
    SCOPED_TRACE(e);
    const Vec3 out = p.truth.end_directions[e];
    const double R = p.truth.end_radii[e];
    for (double depth : {0.0, 0.2, 0.6}) {
      const Vec3 click = p.truth.end_tips[e] - (depth * R) * out + R * perpendicular(out);
      auto cut = cut_across_vessel(p.mesh, p.adj, click);
      ASSERT_TRUE(cut.ok()) << depth << ": " << cut.message();
      size_t same = 0;
      for (const VesselEnd& end : ends.ends)
        same += end.plane.point == cut.value().plane.point &&
                end.plane.normal == cut.value().plane.normal;
      EXPECT_EQ(same, 1u) << depth;
      EXPECT_GT(dot(cut.value().plane.normal, out), std::cos(5 * std::numbers::pi / 180));
      EXPECT_NEAR(cut.value().radius, R, 0.1 * R);
    }
  }
}

/// Surface vertices on end e of the truth (beyond `behind` radii behind
/// `base`, within 1.5 radii of the axis through it), every k-th of them so
/// that about `count` are left.
std::vector<Vec3> points_on_end(const SurfaceMesh& m, const Vec3& base, const Vec3& dir, double R,
                                double behind, size_t count) {
  std::vector<Vec3> all;
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    const Vec3 d = at(m.points, int32_t(v)) - base;
    const double along = dot(d, dir);
    if (along >= -behind * R && norm(d - along * dir) <= 1.5 * R && norm(d) < 3 * R)
      all.push_back(at(m.points, int32_t(v)));
  }
  std::vector<Vec3> some;
  const size_t step = std::max<size_t>(1, all.size() / count);
  for (size_t i = 0; i < all.size(); i += step) some.push_back(all[i]);
  return some;
}

TEST(CutAcrossVessel, AClickAnywhereOnADomedEndCutsAtItsRim) {
  PhantomTruth truth;
  const SurfaceMesh m = testing::capped_phantom(PhantomCapShape::kDome, 0.15, 0.1, &truth);
  const TriangleAdjacency adj = build_adjacency(m);
  for (size_t e : {size_t(0), size_t(2)}) {  // domes 0.3 and 1 radius high
    SCOPED_TRACE(e);
    const Vec3 base = truth.opening_centers[e], dir = truth.end_directions[e];
    const double R = truth.opening_radii[e];
    for (const Vec3& p : points_on_end(m, base, dir, R, 0.25, 5)) {
      auto cut = cut_across_vessel(m, adj, p);
      ASSERT_TRUE(cut.ok()) << point_text(p) << ": " << cut.message();
      // Across the vessel, at the dome's rim or behind it where the click
      // was on the wall.
      const double along = dot(Vec3(cut.value().plane.point) - base, dir);
      EXPECT_LT(along, 0.1 * R) << point_text(p);
      EXPECT_GT(along, -0.5 * R) << point_text(p);
      EXPECT_GT(std::abs(dot(Vec3(cut.value().plane.normal), dir)), std::cos(0.2));
    }
  }
}

TEST(CutAcrossVessel, AClickAnywhereOnAShortWideRootsEndCutsIt) {
  PhantomTruth truth;
  const SurfaceMesh m = testing::phantom(PhantomKind::kRoot, false, 0.2, 0.3, &truth);
  const TriangleAdjacency adj = build_adjacency(m);
  const Vec3 tip = truth.end_tips[0], dir = truth.end_directions[0];
  const double R = truth.end_radii[0];
  for (const Vec3& p : points_on_end(m, tip - R * dir, dir, R, 0.25, 8)) {
    auto cut = cut_across_vessel(m, adj, p);
    ASSERT_TRUE(cut.ok()) << point_text(p) << ": " << cut.message();
    EXPECT_NEAR(cut.value().radius, R, 0.15 * R) << point_text(p);
    EXPECT_GT(std::abs(dot(Vec3(cut.value().plane.normal), dir)), std::cos(0.2));
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
