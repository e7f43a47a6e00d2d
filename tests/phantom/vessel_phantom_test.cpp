#include "core/phantom/vessel_phantom.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/mesh/topology.h"

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
                                           Case{PhantomKind::kTorus, "torus"}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(Phantom, ClosedEndsGiveAClosedSurface) {
  PhantomOptions o;
  o.kind = PhantomKind::kBifurcation;
  o.open_ends = false;
  o.voxel = 0.12;
  PhantomTruth truth;
  auto r = make_vessel_phantom(o, &truth);
  ASSERT_TRUE(r.ok());
  TopologyReport t = analyze_topology(r.value());
  EXPECT_TRUE(t.closed);
  EXPECT_EQ(t.genus, 0);
  EXPECT_EQ(truth.openings, 0);
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
