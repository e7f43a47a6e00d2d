// The model's unit as preparation decides it, and the surfaces that enclose
// no volume.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/io/stl.h"
#include "core/io/vtk_writer.h"
#include "core/pipeline/mesh_job.h"
#include "core/pipeline/option_table.h"
#include "core/pipeline/prepare_surface.h"
#include "core/pipeline/report_json.h"
#include "tests/support/phantoms.h"

namespace vm {
namespace {

/// The closed bifurcation (rounded ends) at `scale`: 10 is a 10 mm vessel
/// in mm, with a 10 mm branches' voxel staircase.
std::vector<uint8_t> closed_bifurcation(double scale) {
  PhantomOptions o;
  o.kind = PhantomKind::kBifurcation;
  o.open_ends = false;
  o.voxel = 0.15;
  o.scale = scale;
  return write_stl_binary(testing::phantom(o));
}

PrepareOptions prepare_options(std::initializer_list<std::pair<const char*, const char*>> given) {
  MeshJobOptions o;
  for (const auto& [id, text] : given) EXPECT_TRUE(set_option_text(o, id, text).ok()) << id;
  return o.prepare;
}

TEST(PrepareUnits, TheGuessIsMadeOnceWhateverIsDoneToTheSurface) {
  const std::vector<uint8_t> stl = closed_bifurcation(10);
  auto plain = prepare_surface(stl);
  ASSERT_TRUE(plain.ok()) << plain.message();
  const ModelUnit& u = plain.value().unit;
  EXPECT_TRUE(u.guessed);
  EXPECT_EQ(u.unit, LengthUnit::kMm) << u.reason;
  for (const PrepareOptions& o :
       {prepare_options({{"clip", "auto"}}),
        prepare_options({{"clip", "auto"}, {"flow_extension", "4"}, {"smooth", "10"}}),
        prepare_options({{"keep_caps", ""}, {"largest_component_only", ""}, {"smooth", "off"}})}) {
    auto other = prepare_surface(stl, o);
    ASSERT_TRUE(other.ok()) << other.message();
    const PreparedSurface& s = other.value();
    EXPECT_EQ(s.unit.unit, u.unit);
    EXPECT_EQ(s.unit.confidence, u.confidence);
    EXPECT_EQ(s.unit.reason, u.reason);
    EXPECT_EQ(s.scale.large_radius, plain.value().scale.large_radius);
    EXPECT_EQ(s.scale.extent, plain.value().scale.extent);
  }
  // A given unit is kept and measured the same.
  auto given = prepare_surface(stl, prepare_options({{"units", "cm"}}));
  ASSERT_TRUE(given.ok());
  EXPECT_EQ(given.value().unit.unit, LengthUnit::kCm);
  EXPECT_FALSE(given.value().unit.guessed);
  EXPECT_EQ(given.value().scale.large_radius, plain.value().scale.large_radius);
}

TEST(PrepareUnits, ASimVascularModelInCentimetresIsGuessedCentimetres) {
  // An aorta of radius 1.2 cm with iliacs, caps labelled as SimVascular
  // labels them (ModelFaceID 1 the wall, 2-4 the caps), written as VTP.
  PhantomOptions o;
  o.kind = PhantomKind::kBifurcation;
  o.voxel = 0.15;
  o.scale = 1.2;
  o.flat_caps = true;
  PhantomTruth truth;
  const SurfaceMesh m = testing::phantom(o, &truth);
  ASSERT_EQ(truth.face_labels.size(), m.num_triangles());
  VtpSurface v;
  v.points = m.points;
  v.triangles = m.triangles;
  v.face_ids = truth.face_labels;
  auto vtp = write_vtp(v);
  ASSERT_TRUE(vtp.ok());
  auto r = prepare_surface(
      std::span(reinterpret_cast<const uint8_t*>(vtp.value().data()), vtp.value().size()));
  ASSERT_TRUE(r.ok()) << r.message();
  const PreparedSurface& s = r.value();
  EXPECT_EQ(s.label_array, "ModelFaceID");
  EXPECT_EQ(s.caps_removed, 3u);
  EXPECT_EQ(s.unit.unit, LengthUnit::kCm) << s.unit.reason;
  EXPECT_TRUE(s.unit.guessed);
  EXPECT_EQ(s.unit.alternative, LengthUnit::kMm);
  EXPECT_FALSE(s.unit.certain);
  // The analysis says what the page asks about.
  const std::string a = analysis_json(s);
  EXPECT_NE(a.find("\"units\":{\"unit\":\"cm\",\"guessed\":true,\"certain\":false,\"reason\":\""),
            std::string::npos)
      << a;
  EXPECT_NE(a.find("\"alternative\":\"mm\",\"measures\":{\"largest_radius\":"), std::string::npos);
  EXPECT_NE(a.find("\"label_array\":\"ModelFaceID\"}"), std::string::npos);
}

TEST(PrepareUnits, ASheetIsRefusedAsEnclosingNoVolumeEarly) {
  // A flat disk of radius 10 (rings of triangles): one opening, no lumen.
  SurfaceMesh disk;
  disk.points = {0, 0, 0};
  const int n = 24, rings = 4;
  for (int k = 1; k <= rings; ++k)
    for (int i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * i / n, r = 10.0 * k / rings;
      disk.points.insert(disk.points.end(), {r * std::cos(a), r * std::sin(a), 0});
    }
  auto at = [&](int k, int i) { return k == 0 ? 0 : 1 + (k - 1) * n + (i % n); };
  for (int k = 0; k < rings; ++k)
    for (int i = 0; i < n; ++i) {
      disk.triangles.insert(disk.triangles.end(), {at(k, i), at(k + 1, i), at(k + 1, i + 1)});
      if (k > 0)
        disk.triangles.insert(disk.triangles.end(), {at(k, i), at(k + 1, i + 1), at(k, i + 1)});
    }
  const std::vector<uint8_t> stl = write_stl_binary(disk);
  auto prepared = prepare_surface(stl);
  ASSERT_TRUE(prepared.ok()) << prepared.message();
  const PreparedSurface& s = prepared.value();
  EXPECT_LT(s.scale.enclosed_share, 0.5);
  const std::string unit(unit_symbol(s.unit.unit));
  bool warned = false;
  for (const std::string& w : s.warnings)
    warned |= w.starts_with("the surface encloses no volume: it is a single sheet");
  EXPECT_TRUE(warned);
  const Status st = check_meshable(s);
  ASSERT_FALSE(st.ok());
  EXPECT_TRUE(st.message().starts_with("cannot mesh: the surface encloses no volume"))
      << st.message();
  EXPECT_NE(st.message().find("e.g. at (0, 0, 0) " + unit), std::string::npos) << st.message();
  // The job refuses it before remeshing, in the same words.
  double reached = 0;
  auto r = run_mesh_job(stl, {}, [&](double f, std::string_view) { return reached = f, true; });
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.message(), st.message());
  EXPECT_LE(reached, 0.2);
  // A vessel's chords meet its wall: no such warning.
  auto tube = prepare_surface(write_stl_binary(testing::phantom(PhantomKind::kTube, true, 0.15)));
  ASSERT_TRUE(tube.ok());
  EXPECT_GT(tube.value().scale.enclosed_share, 0.9);
  EXPECT_TRUE(check_meshable(tube.value()).ok());
}

}  // namespace
}  // namespace vm
