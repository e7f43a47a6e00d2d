// Phase 4 of the preparation (smoothing of voxel staircases) as the
// pipeline runs it, and a mesh job on a raw staircase.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/io/stl.h"
#include "core/mesh/surface_distance.h"
#include "core/phantom/vessel_phantom.h"
#include "core/pipeline/mesh_job.h"
#include "core/pipeline/option_table.h"
#include "core/pipeline/prepare_surface.h"
#include "core/pipeline/report_json.h"
#include "tests/support/phantoms.h"

namespace vm {
namespace {

std::vector<uint8_t> binary_stl(PhantomKind kind, double voxel) {
  PhantomOptions o;
  o.kind = kind;
  o.voxel = voxel;
  o.binary = true;
  return write_stl_binary(testing::phantom(o));
}

PrepareOptions smoothing(const char* text) {
  MeshJobOptions o;
  EXPECT_TRUE(set_option_text(o, "smooth", text).ok()) << text;
  return o.prepare;
}

bool has_warning(const PreparedSurface& s, const std::string& text) {
  for (const std::string& w : s.warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

double largest_move(const SurfaceMesh& a, const SurfaceMesh& b) {
  double worst = 0;
  for (size_t v = 0; v < a.num_vertices(); ++v)
    worst = std::max(worst, std::hypot(a.points[3 * v] - b.points[3 * v],
                                       a.points[3 * v + 1] - b.points[3 * v + 1],
                                       a.points[3 * v + 2] - b.points[3 * v + 2]));
  return worst;
}

TEST(PrepareSmoothing, AStaircaseIsSmoothedByDefault) {
  const auto stl = binary_stl(PhantomKind::kBifurcation, 0.16);
  auto smoothed = prepare_surface(stl);
  auto raw = prepare_surface(stl, smoothing("off"));
  ASSERT_TRUE(smoothed.ok() && raw.ok());
  const PreparedSurface &s = smoothed.value(), &r = raw.value();
  EXPECT_TRUE(s.smoothing.staircase.staircase);
  EXPECT_TRUE(s.smoothing.applied);
  EXPECT_NEAR(s.smoothing.voxel, 0.16, 1e-6);
  EXPECT_GE(s.smoothing.report.passes, 24);
  // Lengths in the model's unit.
  EXPECT_TRUE(has_warning(s, "the surface is a voxel staircase (voxel 0.16 " +
                                 std::string(unit_symbol(s.unit.unit)) + "): smoothed with " +
                                 std::to_string(s.smoothing.report.passes) +
                                 " passes, every vertex within half a voxel; turn it off with "
                                 "{smooth} off"));
  // Vertices moved only: the same triangles, openings and topology, every
  // vertex within half a voxel of where the file had it.
  EXPECT_EQ(s.mesh.triangles, r.mesh.triangles);
  EXPECT_EQ(s.topology.openings.size(), 3u);
  EXPECT_EQ(s.topology.genus, 0);
  EXPECT_LE(largest_move(s.mesh, r.mesh), 0.08 * (1 + 1e-6));  // float STL coordinates
  EXPECT_GT(s.quality_stats.min, r.quality_stats.min);
  // Off: detected and reported, not smoothed.
  EXPECT_TRUE(r.smoothing.staircase.staircase);
  EXPECT_FALSE(r.smoothing.applied);
  EXPECT_FALSE(has_warning(r, "staircase"));
}

TEST(PrepareSmoothing, ASmoothSurfaceIsLeftAloneUnlessPassesAreAsked) {
  const auto stl = write_stl_binary(testing::phantom(PhantomKind::kTube, true, 0.12, 0.3));
  auto automatic = prepare_surface(stl);
  auto off = prepare_surface(stl, smoothing("off"));
  auto passes = prepare_surface(stl, smoothing("5"));
  ASSERT_TRUE(automatic.ok() && off.ok() && passes.ok());
  EXPECT_FALSE(automatic.value().smoothing.staircase.staircase);
  EXPECT_FALSE(automatic.value().smoothing.applied);
  EXPECT_EQ(automatic.value().mesh.points, off.value().mesh.points);
  EXPECT_EQ(automatic.value().warnings, off.value().warnings);
  const PreparedSurface& p = passes.value();
  EXPECT_TRUE(p.smoothing.applied);
  EXPECT_EQ(p.smoothing.mode, Smoothing::Mode::kPasses);
  EXPECT_EQ(p.smoothing.report.passes, 5);
  EXPECT_GT(p.smoothing.voxel, 0);  // the median edge
  EXPECT_LE(largest_move(p.mesh, off.value().mesh), 0.5 * p.smoothing.voxel * (1 + 1e-9));
  EXPECT_TRUE(has_warning(p,
                          "smoothed with 5 passes ({smooth} 5), every vertex within half the "
                          "median edge length"));
}

TEST(PrepareSmoothing, NoBumpOfANoisyMaskIsTakenForACap) {
  // A binary mask with voxel noise: single-voxel bumps whose flat tops,
  // unsmoothed, pass the shape tests of planar caps (they gave bogus
  // openings, then failing layers); they are far narrower than the lumen
  // across their rims, so neither surface loses one.
  PhantomOptions o;
  o.kind = PhantomKind::kTube;
  o.voxel = 0.12;
  o.noise = 0.3;
  o.binary = true;
  auto phantom = make_vessel_phantom(o);
  ASSERT_TRUE(phantom.ok());
  const auto stl = write_stl_binary(phantom.value());
  auto smoothed = prepare_surface(stl);
  auto raw = prepare_surface(stl, smoothing("off"));
  ASSERT_TRUE(smoothed.ok() && raw.ok());
  EXPECT_TRUE(smoothed.value().smoothing.applied);
  EXPECT_EQ(smoothed.value().caps_removed, 0u);
  EXPECT_EQ(smoothed.value().topology.openings.size(), 2u);
  EXPECT_EQ(raw.value().caps_removed, 0u);
  EXPECT_EQ(raw.value().topology.openings.size(), 2u);
}

TEST(PrepareSmoothing, TheAnalysisReportsIt) {
  auto r = prepare_surface(binary_stl(PhantomKind::kTube, 0.16));
  ASSERT_TRUE(r.ok());
  const std::string json = analysis_json(r.value());
  for (const char* key :
       {"\"smoothing\":{\"mode\":\"auto\",\"staircase\":true,\"direction_fraction\":",
        "\"lattice_fraction\":", "\"voxel\":0.1", "\"clamp_voxel\":", "\"spacing\":[",
        "\"applied\":true", "\"passes\":", "\"max_displacement\":", "\"max_displacement_voxels\":",
        "\"volume_change\":"})
    EXPECT_NE(json.find(key), std::string::npos) << key << " in " << json;
  EXPECT_NE(json.find("turn it off with --smooth off"), std::string::npos);
  EXPECT_NE(analysis_json(r.value(), kFaceJs).find("turn it off with smooth off"),
            std::string::npos);
}

TEST(PrepareSmoothing, BadValuesAreRefusedNamingTheOption) {
  for (const char* bad : {"0", "x", "1001", "-1"}) {
    MeshJobOptions o;
    const Status st = set_option_text(o, "smooth", bad);
    ASSERT_FALSE(st.ok()) << bad;
    EXPECT_EQ(st.kind(), ErrorKind::kBadOption);
    EXPECT_EQ(phrase_error(st, kFaceCli),
              "--smooth needs auto, off or a number of smoothing passes from 1 to 1000");
  }
}

TEST(MeshJob, ARawStaircaseMeshesWithLayersAndStaysOnItsInput) {
  const double voxel = 0.16;
  PhantomOptions po;
  po.kind = PhantomKind::kTube;
  po.voxel = voxel;
  po.binary = true;
  auto phantom = make_vessel_phantom(po);
  ASSERT_TRUE(phantom.ok());
  MeshJobOptions o;
  o.verify = true;
  auto r = run_mesh_job(write_stl_binary(phantom.value()), o);
  ASSERT_TRUE(r.ok()) << r.message();
  const MeshJobResult& m = r.value();
  EXPECT_TRUE(m.surface.smoothing.applied);
  EXPECT_EQ(m.output_topology.openings.size(), 2u);
  EXPECT_EQ(m.volume_stats.viscous_layers, 4);
  EXPECT_GE(m.core_quality_stats.min, 0.2);
  EXPECT_EQ(m.remesh_stats.feature_edges, 0u);
  // Every vertex of the raw staircase within a voxel of the wall.
  const DistanceReport gap = distances_to_surface(m.output_surface, phantom.value().points);
  EXPECT_LT(gap.max, voxel);
}

}  // namespace
}  // namespace vm
