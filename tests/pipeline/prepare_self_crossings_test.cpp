// A surface that crosses itself: with {repair} auto the place is re-surfaced
// and said; with {repair} off preparation finds where (analysis, JSON,
// warning), and a later stage's failure on it names the place first.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/io/stl.h"
#include "core/pipeline/mesh_job.h"
#include "core/pipeline/prepare_surface.h"
#include "core/pipeline/report_json.h"
#include "tests/support/pushed_tube.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

PrepareOptions repair_off() {
  PrepareOptions o;
  o.repair = false;
  return o;
}

TEST(PrepareSelfCrossings, ADentThroughTheOppositeWallIsReSurfacedAndTold) {
  auto r = prepare_surface(write_stl_binary(testing::pushed_tube()));
  ASSERT_TRUE(r.ok()) << r.message();
  const PreparedSurface& s = r.value();
  EXPECT_EQ(s.self_crossings.pairs, 0u);
  EXPECT_TRUE(check_meshable(s).ok()) << check_meshable(s).message();
  EXPECT_EQ(s.topology.openings.size(), 2u);
  ASSERT_EQ(s.resurfaced.places.size(), 1u);
  const ResurfacedPlace& p = s.resurfaced.places[0];
  EXPECT_TRUE(p.resolved) << p.why;
  EXPECT_LT(std::abs(p.where[0] + 1) + std::abs(p.where[1]) + std::abs(p.where[2] - 4), 0.7)
      << point_text(p.where);
  bool warned = false;
  for (const std::string& w : s.warnings)
    warned |= w.starts_with("the surface crossed itself at " + point_text(p.where)) &&
              w.find("re-surfaced") != std::string::npos;
  EXPECT_TRUE(warned);
  EXPECT_NE(analysis_json(s).find("\"crossings_resurfaced\":[{\"where\":["), std::string::npos);
  // The whole job then meshes it.
  auto job = run_mesh_job(write_stl_binary(testing::pushed_tube()));
  EXPECT_TRUE(job.ok()) << job.message();
}

TEST(PrepareSelfCrossings, WithRepairOffADentIsFoundAndTold) {
  auto r = prepare_surface(write_stl_binary(testing::pushed_tube()), repair_off());
  ASSERT_TRUE(r.ok()) << r.message();
  const PreparedSurface& s = r.value();
  EXPECT_TRUE(s.self_crossings_checked);
  EXPECT_GT(s.self_crossings.pairs, 0u);
  ASSERT_EQ(s.self_crossings.places.size(), 1u);
  const Vec3& p = s.self_crossings.places[0];
  EXPECT_LT(std::abs(p[0] + 1) + std::abs(p[1]) + std::abs(p[2] - 4), 0.7) << point_text(p);
  bool warned = false;
  for (const std::string& w : s.warnings)
    warned |= w.starts_with("the surface crosses itself at 1 place (") &&
              w.find(point_text(p)) != std::string::npos;
  EXPECT_TRUE(warned);
  const std::string json = analysis_json(s);
  EXPECT_NE(json.find("\"self_crossings\":{\"checked\":true,\"pairs\":" +
                      std::to_string(s.self_crossings.pairs) + ",\"place_count\":1,\"places\":[["),
            std::string::npos)
      << json;
}

TEST(PrepareSelfCrossings, ACleanTubeHasNone) {
  auto r = prepare_surface(write_stl_binary(testing::open_tube(48, 40, 1.0, 8.0)));
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_TRUE(r.value().self_crossings_checked);
  EXPECT_EQ(r.value().self_crossings.pairs, 0u);
  EXPECT_EQ(self_crossing_prefix(r.value()), "");
  for (const std::string& w : r.value().warnings)
    EXPECT_EQ(w.find("crosses itself"), std::string::npos);
}

TEST(PrepareSelfCrossings, AFailingStageNamesTheCrossingFirst) {
  const std::vector<uint8_t> bytes = write_stl_binary(testing::pushed_tube());
  MeshJobOptions off;
  off.prepare.repair = false;
  auto r = run_mesh_job(bytes, off);
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(r.message().starts_with("the input crosses itself at (")) << r.message();
  // What to do, for the page's button: the repair, at the place.
  EXPECT_EQ(r.status().remedy().action, "repair");
  ASSERT_EQ(r.status().remedy().places.size(), 1u);
  const Vec3 place = r.status().remedy().places[0];
  EXPECT_LT(std::abs(place[0] + 1) + std::abs(place[2] - 4), 0.7) << point_text(place);
  // With the model's unit and what to do, before the stage's own words.
  auto prepared = prepare_surface(bytes);
  ASSERT_TRUE(prepared.ok());
  EXPECT_NE(r.message().find(") " + std::string(unit_symbol(prepared.value().unit.unit)) +
                             " (1 place; fix it in the segmentation, or cut that part off with "
                             "{clip_plane}): "),
            std::string::npos)
      << r.message();
  // An option's error is the option's alone.
  MeshJobOptions o = off;
  o.max_elements = 1000;
  auto refused = run_mesh_job(bytes, o);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().kind(), ErrorKind::kBadOption);
  EXPECT_EQ(refused.message().find("crosses itself"), std::string::npos) << refused.message();
}

}  // namespace
}  // namespace vm
