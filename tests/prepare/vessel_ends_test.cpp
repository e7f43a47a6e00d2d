#include "core/prepare/vessel_ends.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <span>

#include "core/geom/vec3.h"
#include "core/mesh/topology.h"
#include "core/phantom/vessel_phantom.h"
#include "tests/support/implicit_vessels.h"
#include "tests/support/phantoms.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

struct Closed {
  SurfaceMesh mesh;
  PhantomTruth truth;
};

Closed closed_phantom(PhantomKind kind, double noise = 0, double voxel = 0.1) {
  Closed c;
  c.mesh = testing::phantom(kind, /*open_ends=*/false, voxel, noise, &c.truth);
  return c;
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

/// Each truth end is found once, with its radius, axis and tip; the cut
/// lies D radii in from the true tip.
void expect_ends_of(const Closed& c, const VesselEnds& found, double D) {
  ASSERT_EQ(found.ends.size(), c.truth.end_tips.size());
  std::vector<int> hits(c.truth.end_tips.size(), 0);
  for (const VesselEnd& e : found.ends) {
    size_t best = 0;
    for (size_t i = 1; i < c.truth.end_tips.size(); ++i)
      if (distance(e.tip, c.truth.end_tips[i]) < distance(e.tip, c.truth.end_tips[best])) best = i;
    ++hits[best];
    // The radius: of the section at the cut (a hemisphere's equator for
    // D = 1), and of the vessel behind it (whose radius varies).
    const double R = c.truth.end_radii[best];
    EXPECT_LT(distance(e.tip, c.truth.end_tips[best]), 0.25 * R) << "end " << best;
    if (D == 1) {
      EXPECT_NEAR(e.cut_radius, R, 0.08 * R) << "end " << best;
    }
    EXPECT_NEAR(e.radius, R, 0.2 * R) << "end " << best;
    // The axis points out, along the centerline's end.
    const auto& dir = c.truth.end_directions[best];
    EXPECT_GT(e.axis[0] * dir[0] + e.axis[1] * dir[1] + e.axis[2] * dir[2], std::cos(0.2))
        << "end " << best;
    // The plane: D local radii in from the true tip, along the true axis.
    double depth = 0;
    for (int k = 0; k < 3; ++k)
      depth += (c.truth.end_tips[best][size_t(k)] - e.plane.point[size_t(k)]) * dir[size_t(k)];
    EXPECT_EQ(e.cut_depth, D);
    EXPECT_NEAR(depth, D * e.radius, 0.1 * R) << "end " << best;
    for (int k = 0; k < 3; ++k) EXPECT_EQ(e.plane.normal[size_t(k)], e.axis[size_t(k)]);
  }
  for (size_t i = 0; i < hits.size(); ++i) EXPECT_EQ(hits[i], 1) << "end " << i;
}

/// The closed phantom of `kind` has `count` true ends, each found once (cut
/// one radius in).
void expect_closed_ends(PhantomKind kind, double noise, size_t count) {
  SCOPED_TRACE(noise);
  const Closed c = closed_phantom(kind, noise);
  ASSERT_EQ(c.truth.end_tips.size(), count);
  expect_ends_of(c, find_vessel_ends(c.mesh), 1.0);
}

TEST(VesselEnds, ClosedTubeHasTwo) { expect_closed_ends(PhantomKind::kTube, 0, 2); }

TEST(VesselEnds, ClosedBifurcationHasThree) {
  for (double noise : {0.0, 0.3}) expect_closed_ends(PhantomKind::kBifurcation, noise, 3);
}

TEST(VesselEnds, TheAneurysmBulbIsNotAnEnd) {
  for (double noise : {0.0, 0.3}) {
    SCOPED_TRACE(noise);
    const Closed c = closed_phantom(PhantomKind::kAneurysm, noise);
    const VesselEnds found = find_vessel_ends(c.mesh);
    expect_ends_of(c, found, 1.0);
    // The bulb's top is at (0.15, 2.0, 1.6): no cut near it.
    const std::array<double, 3> dome = {0.15, 2.0, 1.6};
    for (const VesselEnd& e : found.ends) EXPECT_GT(distance(e.plane.point, dome), 3.0);
  }
}

TEST(VesselEnds, ASidewallAneurysmDomeIsRejectedAndSaidSo) {
  const SurfaceMesh m = testing::sidewall_aneurysm(0.1);
  const VesselEnds found = find_vessel_ends(m);
  ASSERT_EQ(found.ends.size(), 2u);
  for (const VesselEnd& e : found.ends) {
    EXPECT_NEAR(std::abs(e.axis[2]), 1.0, 1e-3);
    EXPECT_NEAR(std::abs(e.plane.point[2]), 6.0, 0.05);
    EXPECT_NEAR(e.radius, 1.0, 0.03);
  }
  // The dome, at (3.8, 0, 0), stands out as much as an end but has no tube
  // behind it.
  ASSERT_EQ(found.rejected.size(), 1u);
  EXPECT_LT(distance(found.rejected[0].where, {3.8, 0, 0}), 1.0);
  EXPECT_NE(found.rejected[0].why.find("no tube"), std::string::npos) << found.rejected[0].why;
}

TEST(VesselEnds, FollowsABendAndAShortBranch) {
  const VesselEnds bend = find_vessel_ends(testing::u_bend(0.1));
  ASSERT_EQ(bend.ends.size(), 2u);
  for (const VesselEnd& e : bend.ends) {
    EXPECT_NEAR(e.axis[2], 1.0, 1e-3);
    EXPECT_NEAR(e.plane.point[2], 5.0, 0.05);
    EXPECT_NEAR(std::abs(e.plane.point[0]), 3.0, 0.05);
  }
  // The side branch reaches 3 from the axis (3.6 of its radii beyond the
  // parent's wall): an end too.
  const VesselEnds branch = find_vessel_ends(testing::short_branch(3.0, 0.1));
  ASSERT_EQ(branch.ends.size(), 3u);
  EXPECT_NEAR(branch.ends[2].radius, 0.5, 0.03);
  EXPECT_NEAR(branch.ends[2].plane.point[0], 3.0, 0.05);
}

TEST(VesselEnds, AFlatEndCutObliquelyIsCutBehindItsFace) {
  for (double degrees : {20.0, 40.0, 55.0, 60.0}) {
    SCOPED_TRACE(degrees);
    const double tilt = degrees * std::numbers::pi / 180;
    const VesselEnds found = find_vessel_ends(testing::oblique_end_tube(tilt, 0.1));
    ASSERT_EQ(found.ends.size(), 2u);
    const VesselEnd& top = found.ends[0].plane.point[2] > 0 ? found.ends[0] : found.ends[1];
    // Perpendicular to the vessel, and below the face's lowest point.
    EXPECT_GT(top.axis[2], std::cos(2 * std::numbers::pi / 180));
    EXPECT_LT(top.plane.point[2], 5 - std::tan(tilt) + 0.05);
    EXPECT_GT(top.plane.point[2], 5 - std::tan(tilt) - 1.0);
    EXPECT_NEAR(top.cut_radius, 1.0, 0.03);
  }
}

TEST(VesselEnds, ATorusOrARingHasNone) {
  const Closed c = closed_phantom(PhantomKind::kTorus);
  ASSERT_EQ(analyze_topology(c.mesh).genus, 1);
  EXPECT_TRUE(find_vessel_ends(c.mesh).ends.empty());
  EXPECT_TRUE(find_vessel_ends(testing::torus(96, 32, 3.0, 1.0)).ends.empty());
}

TEST(VesselEnds, ClipDistanceMovesTheCut) {
  const Closed c = closed_phantom(PhantomKind::kTube);
  for (double D : {0.5, 2.0}) {
    SCOPED_TRACE(D);
    VesselEndOptions o;
    o.clip_distance = D;
    expect_ends_of(c, find_vessel_ends(c.mesh, o), D);
  }
  // Straight legs ending at z = 6 (radius 1): the cut at z = 6 - D.
  const SurfaceMesh bend = testing::u_bend(0.1);
  for (double D : {0.5, 1.5, 3.0}) {
    SCOPED_TRACE(D);
    VesselEndOptions o;
    o.clip_distance = D;
    const VesselEnds found = find_vessel_ends(bend, o);
    ASSERT_EQ(found.ends.size(), 2u);
    for (const VesselEnd& e : found.ends) EXPECT_NEAR(e.plane.point[2], 6 - D, 0.05);
  }
}

TEST(VesselEnds, AShortWideRootIsFound) {
  // A root 1.7 times as wide as the parent radius, its centerline 0.8 of
  // its radius long up to a T-shaped branching: no tube of 2.5 radii
  // behind its end, and the far points' distance passes it by.
  const Closed c = closed_phantom(PhantomKind::kRoot, 0.3, 0.15);
  const VesselEnds found = find_vessel_ends(c.mesh);
  ASSERT_EQ(found.ends.size(), 5u);
  // By decreasing radius: the root first, the only short end.
  const VesselEnd& root = found.ends[0];
  EXPECT_TRUE(root.short_end);
  EXPECT_NEAR(root.radius, c.truth.end_radii[0], 0.1 * c.truth.end_radii[0]);
  EXPECT_LT(distance(root.tip, c.truth.end_tips[0]), 0.25 * c.truth.end_radii[0]);
  EXPECT_GT(dot(root.axis, c.truth.end_directions[0]), std::cos(0.1));
  for (size_t e = 1; e < 5; ++e) EXPECT_FALSE(found.ends[e].short_end) << e;
}

TEST(VesselEnds, AnOpeningIsNoEndAndTheBlindEndsBesideItAre) {
  // The closed bifurcation with its parent vessel cut open: the two blind
  // branches are found, the opening's rim is no end.
  Closed c = closed_phantom(PhantomKind::kBifurcation, 0.3);
  const double R = c.truth.end_radii[0];
  std::array<double, 3> at{};
  for (int k = 0; k < 3; ++k)
    at[size_t(k)] = c.truth.end_tips[0][size_t(k)] - 2 * R * c.truth.end_directions[0][size_t(k)];
  const ClipPlane plane{at, c.truth.end_directions[0]};
  auto open = clip_surface(c.mesh, {}, std::span(&plane, 1));
  ASSERT_TRUE(open.ok()) << open.message();
  const VesselEnds found = find_vessel_ends(open.value().mesh);
  ASSERT_EQ(found.ends.size(), 2u);
  for (const VesselEnd& e : found.ends) {
    EXPECT_GT(distance(e.plane.point, at), 3 * R);
    EXPECT_LT(std::min(distance(e.tip, c.truth.end_tips[1]), distance(e.tip, c.truth.end_tips[2])),
              0.25 * e.radius);
  }
  for (const NotAVesselEnd& r : found.rejected) EXPECT_GT(distance(r.where, at), 3 * R);
}

TEST(VesselEnds, FlatEndsAreEndsToo) {
  // A capped (flat-ended) bifurcation, its caps kept as wall.
  PhantomTruth truth;
  const VesselEnds found = find_vessel_ends(testing::flat_capped_bifurcation(0.1, &truth));
  ASSERT_EQ(found.ends.size(), truth.opening_centers.size());
  for (const VesselEnd& e : found.ends) {
    size_t best = 0;
    for (size_t i = 1; i < truth.opening_centers.size(); ++i)
      if (distance(e.tip, truth.opening_centers[i]) < distance(e.tip, truth.opening_centers[best]))
        best = i;
    const double R = truth.opening_radii[best];
    // The tip is on the flat cap, the cut one radius in.
    EXPECT_LT(distance(e.tip, truth.opening_centers[best]), 0.3 * R);
    EXPECT_NEAR(distance(e.plane.point, truth.opening_centers[best]), R, 0.2 * R);
  }
}

}  // namespace
}  // namespace vm
