#include "core/prepare/recognize_caps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/topology.h"
#include "tests/support/phantoms.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

CapRecognition recognize(const SurfaceMesh& m, const std::vector<int32_t>& labels = {},
                         const std::vector<std::pair<int32_t, std::string>>& names = {}) {
  return recognize_caps(m, build_adjacency(m), labels, names);
}

TEST(RecognizeCaps, FlatEndsOfAClosedTubeByShape) {
  const SurfaceMesh tube = testing::capped_tube(32, 16, 1.0, 6.0);
  const CapRecognition r = recognize(tube);
  ASSERT_EQ(r.caps.size(), 2u);
  for (const RecognizedCap& c : r.caps) {
    EXPECT_EQ(c.label, -1);
    EXPECT_EQ(c.triangles.size(), 32u);
    EXPECT_NEAR(c.radius, 1.0, 0.02);  // a 32-gon's area
    EXPECT_NEAR(std::abs(c.normal[2]), 1.0, 1e-12);
    // Out of the surface: the bottom cap faces -z, the top one +z.
    EXPECT_NEAR(c.normal[2], c.centroid[2] > 3 ? 1.0 : -1.0, 1e-12);
  }
}

TEST(RecognizeCaps, LabelledFacesWithTheirNames) {
  const SurfaceMesh tube = testing::capped_tube(24, 8, 2.0, 5.0);
  // open_tube's triangles first (label 1), then the fans alternate bottom
  // (label 3) and top (label 4).
  std::vector<int32_t> labels(tube.num_triangles(), 1);
  for (size_t t = 2 * 24 * 8; t < labels.size(); ++t) labels[t] = (t - 2 * 24 * 8) % 2 ? 4 : 3;
  const CapRecognition r = recognize(tube, labels, {{3, "aorta"}, {1, "wall"}});
  ASSERT_EQ(r.caps.size(), 2u);
  EXPECT_EQ(r.caps[0].label + r.caps[1].label, 7);
  for (const RecognizedCap& c : r.caps) EXPECT_EQ(c.name, c.label == 3 ? "aorta" : "");
  EXPECT_TRUE(r.notes.empty());
}

TEST(RecognizeCaps, OneLabelForEverythingMeansCapsByShape) {
  // An OBJ with a single group, a VTP whose ModelFaceID is 1 everywhere.
  const SurfaceMesh tube = testing::capped_tube(32, 16, 1.0, 6.0);
  const std::vector<int32_t> one(tube.num_triangles(), 1);
  EXPECT_EQ(recognize(tube, one).caps.size(), 2u);
}

TEST(RecognizeCaps, EachPartOfALabelIsACandidateAndWallBandsNeedNoNote) {
  const SurfaceMesh tube = testing::capped_tube(24, 8, 2.0, 5.0);
  std::vector<int32_t> labels(tube.num_triangles(), 1);
  // Both fans under one label: each connected part is a cap.
  for (size_t t = 2 * 24 * 8; t < labels.size(); ++t) labels[t] = 2;
  EXPECT_EQ(recognize(tube, labels).caps.size(), 2u);
  // A band of the wall under its own label is not planar: no cap, no note.
  for (size_t t = 0; t < 2 * 24; ++t) labels[t] = 5;
  const CapRecognition r = recognize(tube, labels);
  EXPECT_EQ(r.caps.size(), 2u);
  EXPECT_TRUE(r.notes.empty());
}

TEST(RecognizeCaps, ALabelledPlanarAnnulusIsNotedAndKept) {
  // A tube whose bottom end is an annulus (label 2) around a fan (label 3).
  const int n = 16;
  SurfaceMesh m = testing::open_tube(n, 4, 1.0, 3.0);
  std::vector<int32_t> labels(m.num_triangles(), 1);
  const int32_t inner = int32_t(m.num_vertices());
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    m.points.insert(m.points.end(), {0.5 * std::cos(a), 0.5 * std::sin(a), 0.0});
  }
  const int32_t center = int32_t(m.num_vertices());
  m.points.insert(m.points.end(), {0, 0, 0});
  for (int32_t i = 0; i < n; ++i) {
    const int32_t a = i, b = (i + 1) % n, ia = inner + a, ib = inner + b;
    m.triangles.insert(m.triangles.end(), {b, a, ia, b, ia, ib});
    labels.insert(labels.end(), {2, 2});
    m.triangles.insert(m.triangles.end(), {ib, ia, center});
    labels.push_back(3);
  }
  const int32_t top = int32_t(m.num_vertices());
  m.points.insert(m.points.end(), {0, 0, 3.0});
  for (int32_t i = 0; i < n; ++i) {
    m.triangles.insert(m.triangles.end(), {4 * n + i, 4 * n + (i + 1) % n, top});
    labels.push_back(4);
  }
  ASSERT_TRUE(analyze_topology(m).closed);
  const CapRecognition r = recognize(m, labels);
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_NE(r.notes[0].find("face 2 is planar but not a disk"), std::string::npos) << r.notes[0];
  // The inner disk and the top are caps of their own.
  ASSERT_EQ(r.caps.size(), 2u);
  EXPECT_EQ(r.caps[0].label + r.caps[1].label, 7);
}

TEST(RecognizeCaps, RoundedEndsAndStaircasesHaveNoCaps) {
  for (double noise : {0.0, 0.3}) {
    const SurfaceMesh closed = testing::phantom(PhantomKind::kBifurcation, false, 0.1, noise);
    EXPECT_TRUE(recognize(closed).caps.empty()) << "noise " << noise;
  }
  // An open staircase: its flat terraces are no vessel ends.
  const SurfaceMesh open = testing::phantom(PhantomKind::kAneurysm, true, 0.12, 0);
  EXPECT_TRUE(recognize(open).caps.empty());
}

TEST(RecognizeCaps, FlatCappedPhantomGivesOneCapPerVesselEnd) {
  PhantomTruth truth;
  const SurfaceMesh m = testing::flat_capped_bifurcation(0.1, &truth);
  ASSERT_TRUE(analyze_topology(m).closed);
  const CapRecognition r = recognize(m);
  ASSERT_EQ(r.caps.size(), truth.opening_centers.size());
  for (const RecognizedCap& c : r.caps) {
    const size_t i = testing::nearest_truth_opening(truth, c.centroid.data());
    EXPECT_NEAR(c.radius, truth.opening_radii[i], 0.15 * truth.opening_radii[i]);
  }
}

/// The caps of a capped phantom match its cut ends: one each, of `shape`,
/// at the cut (the rim's plane through the cut's centre, along the vessel,
/// of its radius), bulging by the heights expected (sorted, in radii).
void expect_rim_caps(const SurfaceMesh& m, const PhantomTruth& truth, CapShape shape,
                     std::vector<double> heights) {
  const CapRecognition r = recognize(m);
  ASSERT_EQ(r.caps.size(), truth.opening_centers.size());
  std::vector<int> hits(r.caps.size(), 0);
  std::vector<double> found;
  for (const RecognizedCap& c : r.caps) {
    EXPECT_EQ(c.shape, shape);
    EXPECT_TRUE(c.cut_at_rim);
    EXPECT_EQ(c.label, -1);
    const size_t i = testing::nearest_truth_opening(truth, c.centroid.data());
    ++hits[i];
    const double R = truth.opening_radii[i];
    EXPECT_NEAR(c.radius, R, 0.1 * R);
    const Vec3 d = Vec3(c.centroid) - Vec3(truth.opening_centers[i]);
    EXPECT_LT(norm(d), 0.15 * R);
    EXPECT_GT(dot(Vec3(c.normal), Vec3(truth.end_directions[i])), std::cos(0.15));
    found.push_back(c.height / c.radius);
  }
  for (int h : hits) EXPECT_EQ(h, 1);
  std::sort(found.begin(), found.end());
  for (size_t i = 0; i < heights.size() && i < found.size(); ++i)
    EXPECT_NEAR(found[i], heights[i], 0.06) << i;
}

TEST(RecognizeCaps, FansAroundALiftedApexByTheirRim) {
  // Fans of a capping tool (apex 0.1 radius off the cut) on a noisy wall.
  PhantomTruth truth;
  const SurfaceMesh m = testing::capped_phantom(PhantomCapShape::kFan, 0.1, 0.3, &truth);
  expect_rim_caps(m, truth, CapShape::kFan, {0.1, 0.1, 0.1});
}

TEST(RecognizeCaps, DomesByTheirRimCrease) {
  // Domes rising 0.3, 0.6 and 1 radius (creases of 59, 40 and 27 degrees).
  PhantomTruth truth;
  const SurfaceMesh m = testing::capped_phantom(PhantomCapShape::kDome, 0.1, 0.1, &truth);
  expect_rim_caps(m, truth, CapShape::kDome, {0.3, 0.6, 1.0});
}

TEST(RecognizeCaps, TouchingFlatFacesAreNotCaps) {
  // A cube: six flat faces at right angles, each touching the others.
  SurfaceMesh cube;
  cube.points = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  cube.triangles = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                    1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
  const CapRecognition r = recognize(cube);
  EXPECT_TRUE(r.caps.empty());
}

}  // namespace
}  // namespace vm
