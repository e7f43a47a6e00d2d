#include "core/prepare/flow_extensions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/mesh/enclosed_volume.h"
#include "core/mesh/self_intersection.h"
#include "core/pipeline/option_table.h"
#include "core/pipeline/prepare_surface.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

/// The volume enclosed by `m` with each opening closed by a fan to its
/// centroid.
double closed_volume(SurfaceMesh m) {
  for (const Opening& op : analyze_topology(m).openings) {
    const int32_t c = int32_t(m.num_vertices());
    m.points.insert(m.points.end(), op.centroid.begin(), op.centroid.end());
    for (size_t i = 0; i < op.loop.size(); ++i)
      m.triangles.insert(m.triangles.end(), {op.loop[(i + 1) % op.loop.size()], op.loop[i], c});
  }
  return enclosed_volume(m);
}

TEST(FlowExtensions, ExtendAnOpenTubeStraightAlongItsAxis) {
  SurfaceMesh tube = testing::open_tube(24, 6, 1.0, 4.0);
  const TopologyReport before = analyze_topology(tube);
  ASSERT_EQ(before.openings.size(), 2u);
  const double volume_before = closed_volume(tube);
  std::vector<int32_t> labels(tube.num_triangles(), 7), opening_of;
  auto r = add_flow_extensions(tube, &labels, before.openings, {3.0, 2.0}, &opening_of);
  ASSERT_TRUE(r.ok()) << r.message();
  ASSERT_EQ(r.value().size(), 2u);
  EXPECT_EQ(labels.size(), tube.num_triangles());
  for (int32_t l : labels) EXPECT_EQ(l, 7);
  EXPECT_EQ(opening_of.size(), tube.num_vertices() - 24 * 7);
  const TopologyReport after = analyze_topology(tube);
  EXPECT_EQ(after.components, 1);
  EXPECT_EQ(after.genus, 0);
  EXPECT_EQ(after.nonmanifold_edges, 0u);
  ASSERT_EQ(after.openings.size(), 2u);
  for (size_t o = 0; o < 2; ++o) {
    const Opening& was = before.openings[o];
    const Opening& now = after.openings[o];
    const double length = (o == 0 ? 3.0 : 2.0) * was.radius;
    // Moved out along the normal by the length, same area and normal.
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(now.centroid[size_t(k)], was.centroid[size_t(k)] + length * was.normal[size_t(k)],
                  1e-9);
      EXPECT_NEAR(now.normal[size_t(k)], was.normal[size_t(k)], 1e-9);
    }
    EXPECT_NEAR(now.radius, was.radius, 1e-9);
    // The end is a planar circle.
    for (int32_t v : now.loop) {
      const double* p = &tube.points[3 * size_t(v)];
      double d[3], along = 0, r2 = 0;
      for (int k = 0; k < 3; ++k) d[k] = p[k] - now.centroid[size_t(k)];
      for (int k = 0; k < 3; ++k) along += d[k] * now.normal[size_t(k)];
      for (int k = 0; k < 3; ++k) r2 += std::pow(d[k] - along * now.normal[size_t(k)], 2);
      EXPECT_NEAR(along, 0, 1e-9);
      // A regular 24-gon of the opening's area.
      const double angle = 2 * std::numbers::pi / 24;
      EXPECT_NEAR(std::sqrt(r2), was.radius * std::sqrt(angle / std::sin(angle)), 1e-9);
    }
  }
  // Outward, and closed by fans at the openings the volume grew by the two
  // extensions: straight prisms of the 24-gon's area here (the tube's rims
  // are already that 24-gon, so the blend is straight).
  const double area = before.openings[0].radius * before.openings[0].radius * std::numbers::pi;
  EXPECT_NEAR(closed_volume(tube), volume_before + area * 5.0 * before.openings[0].radius,
              1e-9 * volume_before);
  EXPECT_EQ(find_self_intersections(tube).pairs, 0u);
}

TEST(FlowExtensions, ALongExtensionOfAFlaredEndStaysATube) {
  // A tube widening from radius 1 to 2 (wall 14 degrees off the axis at
  // both rims), extended by 40 radii at both ends: the join leaves each
  // rim in the wall's direction, yet no ring may swing out or pinch. Every
  // new vertex stays between the rim's and the end circle's radius from the
  // axis, with 10% slack for the join's smooth overshoot (a blend over half
  // the extension put rings between 0.29 and 3.4 from it).
  SurfaceMesh tube = testing::open_tube(32, 8, 1.0, 4.0);
  for (size_t v = 0; v < tube.num_vertices(); ++v) {
    const double s = 1 + 0.25 * tube.points[3 * v + 2];
    tube.points[3 * v] *= s;
    tube.points[3 * v + 1] *= s;
  }
  const TopologyReport before = analyze_topology(tube);
  ASSERT_EQ(before.openings.size(), 2u);
  const size_t old_vertices = tube.num_vertices();
  std::vector<int32_t> opening_of;
  auto r = add_flow_extensions(tube, nullptr, before.openings, {40.0, 40.0}, &opening_of);
  ASSERT_TRUE(r.ok()) << r.message();
  ASSERT_EQ(opening_of.size(), tube.num_vertices() - old_vertices);
  const double angle = 2 * std::numbers::pi / 32;
  for (size_t i = 0; i < opening_of.size(); ++i) {
    const Opening& op = before.openings[size_t(opening_of[i])];
    // The rim is a circle about the z axis: its radius, and the end's.
    const double* rim = &tube.points[3 * size_t(op.loop[0])];
    const double rim_radius = std::hypot(rim[0], rim[1]);
    const double end_radius = op.radius * std::sqrt(angle / std::sin(angle));
    const double* p = &tube.points[3 * (old_vertices + i)];
    const double d = std::hypot(p[0], p[1]);
    EXPECT_GE(d, 0.9 * std::min(rim_radius, end_radius)) << "vertex " << i;
    EXPECT_LE(d, 1.1 * std::max(rim_radius, end_radius)) << "vertex " << i;
  }
  EXPECT_EQ(find_self_intersections(tube).pairs, 0u);
}

TEST(FlowExtensions, AnExtensionIntoTheWallIsRefusedWithAPlace) {
  // A U-shaped tube: its two ends face the same way, side by side; a long
  // extension of one is fine, but a bent end aimed at the other tube is not.
  SurfaceMesh tube = testing::open_tube(16, 4, 1.0, 4.0);
  SurfaceMesh other = testing::open_tube(16, 4, 1.0, 4.0);
  // The second tube across the first's axis, 6 beyond its top end.
  for (size_t v = 0; v < other.num_vertices(); ++v) {
    double* p = &other.points[3 * v];
    const double x = p[0], z = p[2];
    p[0] = z - 2.0;
    p[2] = 10.0 + x;
  }
  const int32_t offset = int32_t(tube.num_vertices());
  tube.points.insert(tube.points.end(), other.points.begin(), other.points.end());
  for (int32_t v : other.triangles) tube.triangles.push_back(v + offset);
  const TopologyReport t = analyze_topology(tube);
  // The opening at z = 4 (facing +z): extended by 8 radii it reaches z = 12.
  std::vector<double> lengths(t.openings.size(), 0);
  for (size_t o = 0; o < t.openings.size(); ++o)
    if (t.openings[o].normal[2] > 0.9 && t.openings[o].centroid[0] > -0.5) lengths[o] = 8;
  auto r = add_flow_extensions(tube, nullptr, t.openings, lengths, nullptr);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("runs into the surface near ("), std::string::npos) << r.message();
  EXPECT_NE(r.message().find("{flow_extension} K=L"), std::string::npos);
}

TEST(FlowExtensions, ThePreparedSurfaceKeepsTheOpeningsOrderAndSources) {
  const std::vector<uint8_t> stl = write_stl_binary(testing::open_tube(24, 6, 1.0, 4.0));
  MeshJobOptions o;
  ASSERT_TRUE(set_option_text(o, "flow_extension", "2=4").ok());
  auto s = prepare_surface(stl, o.prepare);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_EQ(s.value().opening_sources.size(), 2u);
  double extended = 0;
  for (const OpeningSource& src : s.value().opening_sources) extended += src.extension;
  EXPECT_NEAR(extended, 4 * s.value().topology.openings[0].radius, 1e-9);
  EXPECT_GT(s.value().opening_sources[1].extension, 0);
  ASSERT_TRUE(set_option_text(o, "flow_extension", "3=1").ok());
  auto bad = prepare_surface(stl, o.prepare);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(phrase_error(bad.status(), kFaceCli),
            "--flow-extension names opening 3, but there are 2 openings");
}

}  // namespace
}  // namespace vm
