// The written wall keeps the remeshed wall's quality where boundary
// recovery has trouble on it or on the layer front, end to end through the
// mesh job: points on the viscous layer's front stay in its top slice
// (core/layers/absorb_front_points.h), wall edges are flipped rather than
// split (core/layers/flip_wall_edges.h), points that still split the wall
// slide along their edge (core/layers/slide_wall_points.h).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/io/stl.h"
#include "core/mesh/volume_check.h"
#include "core/pipeline/mesh_job.h"
#include "core/pipeline/report_json.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

// A regular tube, meshed as it is: its rings of cocircular vertices make a
// Delaunay tetrahedralization without many of its edges (and of its
// layer front's), so that recovery needs Steiner points there (10 on the
// front, 8 on the wall without layers, before this stage's changes).
std::vector<uint8_t> tube_stl() { return write_stl_binary(testing::open_tube(24, 20, 1.0, 3.0)); }

double written_wall_min(const MeshJobResult& r) {
  for (const SurfaceGroupQuality& g : r.written_quality)
    if (g.name == "wall") return g.quality.min;
  ADD_FAILURE() << "no wall group";
  return 0;
}

TEST(WrittenWallQuality, RecoveryKeepsTheWallsQuality) {
  const std::vector<uint8_t> stl = tube_stl();
  struct Variant {
    const char* name;
    int layers, wall_layers;
    bool prisms;
  };
  for (const Variant& v :
       {Variant{"viscous layer", 4, 0, false}, Variant{"viscous layer, prisms kept", 4, 0, true},
        Variant{"no layer", 0, 0, false}, Variant{"vessel wall only", 0, 4, false},
        Variant{"viscous layer and vessel wall", 4, 4, false}}) {
    SCOPED_TRACE(v.name);
    MeshJobOptions o;
    o.remesh = false;  // the tube as it is: the remeshed wall is the input
    o.viscous.layers = v.layers;
    o.vessel.layers = v.wall_layers;
    o.vessel.thickness_fraction = 0.1;
    o.keep_prisms = v.prisms;
    auto r = run_mesh_job(stl, o);
    ASSERT_TRUE(r.ok()) << r.message();
    const MeshJobResult& res = r.value();
    const VolumeStats& vs = res.volume_stats;
    // The case is one: recovery had to add points or flip wall edges.
    EXPECT_GT(vs.steiner_points + vs.wall_edges_flipped, 0u);
    // Valid: no inverted element, conforming, boundary = written surfaces.
    const auto check = check_volume_mesh(res.volume);
    EXPECT_TRUE(check.ok()) << check.message();
    // The written wall within 0.05 of the remeshed wall's minimum.
    EXPECT_GE(written_wall_min(res), res.output_quality_stats.min - 0.05)
        << vs.steiner_points << " Steiner points (" << vs.absorbed_steiner_points
        << " in the layer, " << vs.wall_steiner_points << " on the wall), " << vs.wall_edges_flipped
        << " wall edges flipped";
    // The counts add up and the changes are reported where they are.
    EXPECT_LE(vs.absorbed_steiner_points + vs.wall_steiner_points, vs.steiner_points);
    EXPECT_LE(vs.reoptimized_steiner_points, vs.wall_steiner_points);
    EXPECT_EQ(vs.wall_change_places.size(), vs.wall_edges_flipped + vs.wall_steiner_points);
    if (v.layers > 0 && !v.prisms) {
      // The top slice takes the front's points: the wall is untouched.
      EXPECT_EQ(vs.absorbed_steiner_points, vs.front_steiner_points);
      EXPECT_EQ(vs.wall_change_places.size(), 0u);
      EXPECT_EQ(written_wall_min(res), res.output_quality_stats.min);
    }
    bool warned = false;
    for (const std::string& w : res.warnings) warned |= w.find("changed the wall") != w.npos;
    EXPECT_EQ(warned, !vs.wall_change_places.empty());
    const std::string json = mesh_report_json(res);
    EXPECT_NE(json.find("\"wall_recovery\""), json.npos);
    EXPECT_NE(json.find("\"written_wall_quality_min\""), json.npos);
  }
}

TEST(WrittenWallQuality, SameMeshOnOneAndTwoThreads) {
  const std::vector<uint8_t> stl = tube_stl();
  for (int layers : {4, 0}) {
    VolumeMesh meshes[2];
    for (int threads : {1, 2}) {
      MeshJobOptions o;
      o.remesh = false;
      o.viscous.layers = layers;
      o.threads = threads;
      auto r = run_mesh_job(stl, o);
      ASSERT_TRUE(r.ok()) << r.message();
      meshes[threads - 1] = r.value().volume;
    }
    EXPECT_EQ(meshes[0].points, meshes[1].points) << layers << " layers";
    EXPECT_EQ(meshes[0].tets, meshes[1].tets) << layers << " layers";
    EXPECT_EQ(meshes[0].triangles, meshes[1].triangles) << layers << " layers";
  }
}

}  // namespace
}  // namespace vm
