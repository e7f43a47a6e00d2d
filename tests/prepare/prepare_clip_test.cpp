// Phases 5 and 6 of the preparation (core/pipeline/prepare_surface_openings.cpp):
// caps removed (fans and domes cut at their rims), blind vessel ends cut
// open by default (closed surfaces or not), and cuts by given planes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <span>
#include <string>

#include "core/geom/vec3.h"
#include "core/io/stl.h"
#include "core/phantom/vessel_phantom.h"
#include "core/pipeline/prepare_surface.h"
#include "core/pipeline/report_json.h"
#include "tests/support/phantoms.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

std::vector<uint8_t> closed_phantom_stl(PhantomKind kind, double noise, bool flat_caps = false) {
  PhantomOptions o;
  o.kind = kind;
  o.voxel = 0.1;
  o.noise = noise;
  o.open_ends = flat_caps;
  o.flat_caps = flat_caps;
  return write_stl_binary(testing::phantom(o));
}

bool has_warning(const PreparedSurface& s, const std::string& text) {
  return std::any_of(s.warnings.begin(), s.warnings.end(),
                     [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

void expect_clip_openings(const PreparedSurface& s, size_t count) {
  ASSERT_EQ(s.topology.openings.size(), count);
  ASSERT_EQ(s.opening_sources.size(), count);
  for (const OpeningSource& src : s.opening_sources) EXPECT_EQ(src.kind, OpeningSource::kClip);
  EXPECT_EQ(s.topology.genus, 0);
  EXPECT_EQ(s.topology.components, 1);
  EXPECT_EQ(s.topology.nonmanifold_edges, 0u);
  EXPECT_FALSE(s.topology.closed);
  EXPECT_TRUE(check_meshable(s).ok());
  EXPECT_EQ(s.clips.size(), count);
}

TEST(PrepareClip, ClipAutoOpensEveryVesselEndOfAClosedSurface) {
  PrepareOptions o;
  o.clip_auto = true;
  for (double noise : {0.0, 0.3}) {
    SCOPED_TRACE(noise);
    auto r = prepare_surface(closed_phantom_stl(PhantomKind::kAneurysm, noise), o);
    ASSERT_TRUE(r.ok()) << r.message();
    expect_clip_openings(r.value(), 3);
    EXPECT_TRUE(has_warning(r.value(), "cut 3 vessel ends open ({clip} auto, 1 local radius in"));
    EXPECT_FALSE(has_warning(r.value(), "the surface is closed"));
    // The parent vessel (radius 1) is the largest opening.
    EXPECT_NEAR(r.value().topology.openings[0].radius, 1.0, 0.05);
  }
  auto tube = prepare_surface(closed_phantom_stl(PhantomKind::kTube, 0), o);
  ASSERT_TRUE(tube.ok()) << tube.message();
  expect_clip_openings(tube.value(), 2);
}

TEST(PrepareClip, FlatEndsKeptAsWallAreCutToo) {
  PrepareOptions o;
  o.clip_auto = true;
  o.keep_caps = true;
  auto r = prepare_surface(closed_phantom_stl(PhantomKind::kBifurcation, 0.3, true), o);
  ASSERT_TRUE(r.ok()) << r.message();
  expect_clip_openings(r.value(), 3);
  EXPECT_EQ(r.value().caps_removed, 0u);
}

TEST(PrepareClip, AClosedSurfaceWithoutClippingIsWarnedAbout) {
  PrepareOptions off;
  off.clip_auto = false;
  auto r = prepare_surface(closed_phantom_stl(PhantomKind::kBifurcation, 0), off);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_TRUE(r.value().topology.closed);
  EXPECT_TRUE(has_warning(r.value(),
                          "the surface is closed: it has no opening to be an inlet or outlet; 3 "
                          "vessel ends were found: cut them open with {clip} auto (or give "
                          "{clip_plane} or {clip_at})"));
  // The proposals are the cuts clip auto (the default) makes.
  auto opened = prepare_surface(closed_phantom_stl(PhantomKind::kBifurcation, 0));
  ASSERT_TRUE(opened.ok()) << opened.message();
  ASSERT_EQ(r.value().clip_proposals.size(), 3u);
  EXPECT_TRUE(opened.value().clip_proposals.empty());
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(r.value().clip_proposals[i].plane.point, opened.value().clips[i].plane.point);
    EXPECT_GT(dot(r.value().clip_proposals[i].plane.normal, opened.value().clips[i].plane.normal),
              1 - 1e-12);
  }
  // A torus has no vessel end: clip auto says so and cuts nothing.
  auto ring = prepare_surface(closed_phantom_stl(PhantomKind::kTorus, 0));
  ASSERT_TRUE(ring.ok()) << ring.message();
  EXPECT_TRUE(ring.value().topology.closed);
  EXPECT_TRUE(has_warning(ring.value(), "{clip} auto found no vessel end to cut"));
}

TEST(PrepareClip, ClipAtCutsAcrossTheVesselAtAPoint) {
  // A closed straight tube along z from 0 to 8: a click beside it at z = 6
  // cuts off the top end, perpendicular to the tube.
  PrepareOptions o;
  o.keep_caps = true;
  o.clip_auto = false;
  o.clip_at = {{1.4, 0.2, 6.0}};
  auto r = prepare_surface(write_stl_binary(testing::capped_tube(40, 64, 1.0, 8.0)), o);
  ASSERT_TRUE(r.ok()) << r.message();
  const PreparedSurface& s = r.value();
  ASSERT_EQ(s.topology.openings.size(), 1u);
  EXPECT_EQ(s.opening_sources[0].kind, OpeningSource::kClip);
  EXPECT_NEAR(s.topology.openings[0].centroid[2], 6.0, 0.13);
  EXPECT_NEAR(std::abs(s.topology.openings[0].normal[2]), 1.0, 1e-6);
  EXPECT_TRUE(has_warning(s, "cut across the vessel at (1.4, 0.2, 6): an opening at"));
  EXPECT_EQ(s.opening_sources[0].shape, OpeningSource::kPoint);
  // The other end stays blind, proposed, with clip off; clip auto cuts it
  // after the cut given.
  ASSERT_EQ(s.clip_proposals.size(), 1u);
  EXPECT_LT(s.clip_proposals[0].plane.point[2], 1.5);
  o.clip_auto = true;
  auto both = prepare_surface(write_stl_binary(testing::capped_tube(40, 64, 1.0, 8.0)), o);
  ASSERT_TRUE(both.ok()) << both.message();
  ASSERT_EQ(both.value().topology.openings.size(), 2u);
  EXPECT_TRUE(both.value().clip_proposals.empty());
  for (const OpeningSource& src : both.value().opening_sources) {
    EXPECT_EQ(src.kind, OpeningSource::kClip);
    EXPECT_TRUE(src.shape == OpeningSource::kPoint || src.shape == OpeningSource::kBlindEnd);
  }
  // On the flat end's centre, where the vessel is no tube: the end's cut,
  // one radius in from its face (the one clip auto makes there).
  o.clip_auto = false;
  o.clip_at = {{0, 0, 8.5}};
  auto flat = prepare_surface(write_stl_binary(testing::capped_tube(40, 64, 1.0, 8.0)), o);
  ASSERT_TRUE(flat.ok()) << flat.message();
  ASSERT_EQ(flat.value().topology.openings.size(), 1u);
  EXPECT_NEAR(flat.value().topology.openings[0].centroid[2], 7.0, 0.13);
  EXPECT_NEAR(std::abs(flat.value().topology.openings[0].normal[2]), 1.0, 1e-6);
  // On an aneurysm's dome, no vessel: refused, saying where.
  o.clip_at = {{0.15, 2.0, 1.6}};
  auto none = prepare_surface(closed_phantom_stl(PhantomKind::kAneurysm, 0), o);
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.message().find("cannot cut across the vessel at ("), std::string::npos)
      << none.message();
}

TEST(PrepareClip, PlanesCutAnySurfaceAndTheirOpeningsSayClip) {
  // A capped tube: the caps become openings, then a plane cuts off the top.
  const SurfaceMesh tube = testing::capped_tube(32, 16, 1.0, 6.0);
  PrepareOptions o;
  o.clip_planes = {{{0, 0, 4.2}, {0, 0, 1}}};
  auto r = prepare_surface(write_stl_binary(tube), o);
  ASSERT_TRUE(r.ok()) << r.message();
  const PreparedSurface& s = r.value();
  ASSERT_EQ(s.topology.openings.size(), 2u);
  int caps = 0, clips = 0;
  for (size_t i = 0; i < 2; ++i) {
    const OpeningSource::Kind kind = s.opening_sources[i].kind;
    caps += kind == OpeningSource::kCap;
    clips += kind == OpeningSource::kClip;
    if (kind == OpeningSource::kClip) {
      EXPECT_NEAR(s.topology.openings[i].centroid[2], 4.2, 1e-9);
    }
  }
  EXPECT_EQ(caps, 1);
  EXPECT_EQ(clips, 1);
  EXPECT_TRUE(has_warning(s, "cut by the plane at (0, 0, 4.2)"));
  // A plane that misses: an error with its point.
  o.clip_planes = {{{0, 30, 3}, {0, 0, 1}}};
  auto miss = prepare_surface(write_stl_binary(tube), o);
  ASSERT_FALSE(miss.ok());
  EXPECT_NE(miss.message().find("the plane at (0, 30, 3) does not cut the surface within"),
            std::string::npos)
      << miss.message();
}

}  // namespace
}  // namespace vm

namespace vm {
namespace {

TEST(PrepareClip, ByDefaultEveryBlindEndIsOpenedAndTheWidestRootIsTheInlet) {
  // A closed tree whose root is short and wider than its branches.
  PhantomTruth truth;
  auto r = prepare_surface(
      write_stl_binary(testing::phantom(PhantomKind::kRoot, false, 0.15, 0.3, &truth)));
  ASSERT_TRUE(r.ok()) << r.message();
  const PreparedSurface& s = r.value();
  expect_clip_openings(s, 5);
  for (const OpeningSource& src : s.opening_sources) EXPECT_EQ(src.shape, OpeningSource::kBlindEnd);
  // The inlet (the largest opening) is the root's, one radius in from its
  // tip.
  const Opening& inlet = s.topology.openings[0];
  EXPECT_NEAR(inlet.radius, truth.end_radii[0], 0.1 * truth.end_radii[0]);
  double along = 0;
  for (size_t k = 0; k < 3; ++k)
    along += (truth.end_tips[0][k] - inlet.centroid[k]) * truth.end_directions[0][k];
  EXPECT_NEAR(along, truth.end_radii[0], 0.2 * truth.end_radii[0]);
  EXPECT_TRUE(has_warning(s, "(a short, wide root)"));
  EXPECT_NE(analysis_json(s).find("\"source\":\"clip\",\"shape\":\"blind_end\""),
            std::string::npos);
}

TEST(PrepareClip, BlindEndsBesideAnOpeningAreOpenedOrKeptWithClipOff) {
  // The closed bifurcation with its parent vessel cut open in the file.
  PhantomTruth truth;
  const SurfaceMesh closed = testing::phantom(PhantomKind::kBifurcation, false, 0.1, 0.3, &truth);
  const double R = truth.end_radii[0];
  std::array<double, 3> at{};
  for (size_t k = 0; k < 3; ++k) at[k] = truth.end_tips[0][k] - 2 * R * truth.end_directions[0][k];
  const ClipPlane plane{at, truth.end_directions[0]};
  auto cut = clip_surface(closed, {}, std::span(&plane, 1));
  ASSERT_TRUE(cut.ok()) << cut.message();
  const std::vector<uint8_t> bytes = write_stl_binary(cut.value().mesh);
  auto r = prepare_surface(bytes);
  ASSERT_TRUE(r.ok()) << r.message();
  ASSERT_EQ(r.value().topology.openings.size(), 3u);
  size_t file = 0, clips = 0;
  for (const OpeningSource& src : r.value().opening_sources) {
    file += src.kind == OpeningSource::kFile;
    clips += src.kind == OpeningSource::kClip && src.shape == OpeningSource::kBlindEnd;
  }
  EXPECT_EQ(file, 1u);
  EXPECT_EQ(clips, 2u);
  EXPECT_TRUE(has_warning(r.value(), "cut 2 vessel ends open ({clip} auto"));
  EXPECT_FALSE(has_warning(r.value(), "open already"));
  // The parent vessel's opening, in the file, is still the inlet.
  EXPECT_NEAR(r.value().topology.openings[0].radius, R, 0.1 * R);
  // {clip} off: the two blind ends are kept, proposed and said.
  PrepareOptions off;
  off.clip_auto = false;
  auto kept = prepare_surface(bytes, off);
  ASSERT_TRUE(kept.ok()) << kept.message();
  EXPECT_EQ(kept.value().topology.openings.size(), 1u);
  EXPECT_EQ(kept.value().clip_proposals.size(), 2u);
  EXPECT_TRUE(has_warning(kept.value(), "2 blind vessel ends were kept closed ({clip} off)"));
}

TEST(PrepareClip, FansAndDomesBecomeOpeningsAtTheirRims) {
  struct Case {
    PhantomCapShape shape;
    double noise;
    OpeningSource::Shape source;
    const char* said;
  };
  for (const Case& c :
       {Case{PhantomCapShape::kFan, 0.3, OpeningSource::kFan, "(0 planar, 3 fans, 0 domes)"},
        Case{PhantomCapShape::kDome, 0.1, OpeningSource::kDome, "(0 planar, 0 fans, 3 domes)"}}) {
    SCOPED_TRACE(c.said);
    PhantomTruth truth;
    auto r =
        prepare_surface(write_stl_binary(testing::capped_phantom(c.shape, 0.1, c.noise, &truth)));
    ASSERT_TRUE(r.ok()) << r.message();
    const PreparedSurface& s = r.value();
    ASSERT_EQ(s.topology.openings.size(), 3u);
    EXPECT_EQ(s.caps_removed, 3u);
    EXPECT_TRUE(s.clips.empty());
    EXPECT_TRUE(check_meshable(s).ok());
    EXPECT_TRUE(has_warning(s, std::string("3 caps were recognised and removed ") + c.said));
    for (size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(s.opening_sources[i].kind, OpeningSource::kCap);
      EXPECT_EQ(s.opening_sources[i].shape, c.source);
      // At the rim: the cut's plane, planar.
      const Opening& op = s.topology.openings[i];
      const size_t t = testing::nearest_truth_opening(truth, op.centroid.data());
      const double R = truth.opening_radii[t];
      double along = 0;
      for (size_t k = 0; k < 3; ++k)
        along += (op.centroid[k] - truth.opening_centers[t][k]) * truth.end_directions[t][k];
      EXPECT_LT(std::abs(along), 0.1 * R) << i;
      EXPECT_NEAR(op.radius, R, 0.1 * R) << i;
      for (int32_t v : op.loop) {
        double off = 0;
        for (size_t k = 0; k < 3; ++k)
          off += (s.mesh.points[3 * size_t(v) + k] - op.centroid[k]) * op.normal[k];
        ASSERT_LT(std::abs(off), 1e-6 * R);
      }
    }
    EXPECT_NE(analysis_json(s).find(std::string("\"source\":\"cap\",\"shape\":\"") +
                                    opening_shape_name(c.source) + "\""),
              std::string::npos);
  }
}

TEST(PrepareSpecks, SmallSeparatePiecesAreRemovedSayingWhere) {
  // A tube and, far away, a stray triangle and a small closed blob.
  SurfaceMesh m = testing::open_tube(32, 16, 1.0, 6.0);
  auto add = [&](const SurfaceMesh& piece, const Vec3& shift) {
    const int32_t first = int32_t(m.num_vertices());
    for (size_t v = 0; v < piece.num_vertices(); ++v)
      for (size_t k = 0; k < 3; ++k) m.points.push_back(piece.points[3 * v + k] + shift[k]);
    for (int32_t c : piece.triangles) m.triangles.push_back(first + c);
  };
  SurfaceMesh stray;
  stray.points = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  stray.triangles = {0, 1, 2};
  add(stray, {1e6, 0, 0});
  add(testing::tetrahedron(), {0, 50, 0});
  auto r = prepare_surface(write_stl_binary(m));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().specks_removed, 2u);
  EXPECT_EQ(r.value().topology.components, 1);
  EXPECT_EQ(r.value().mesh.num_triangles(), size_t(2 * 32 * 16));
  EXPECT_LT(r.value().box.diagonal(), 10);
  EXPECT_TRUE(has_warning(r.value(),
                          "removed 2 small separate pieces (5 triangles, each under 1% "
                          "of the surface), e.g. at ("));
  // A second vessel of its own size is no speck: several components remain.
  SurfaceMesh two = testing::open_tube(32, 16, 1.0, 6.0);
  m = two;
  add(two, {10, 0, 0});
  auto both = prepare_surface(write_stl_binary(m));
  ASSERT_TRUE(both.ok()) << both.message();
  EXPECT_EQ(both.value().specks_removed, 0u);
  EXPECT_EQ(both.value().topology.components, 2);
}

}  // namespace
}  // namespace vm
