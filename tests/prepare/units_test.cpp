#include "core/prepare/units.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/pipeline/option_values.h"
#include "tests/support/phantoms.h"

namespace vm {
namespace {

/// A model's scale from its sizes in millimetres, written in `unit`.
VesselScale in_unit(double large, double median, double small, double extent, LengthUnit unit,
                    std::string labels = "") {
  const double per_mm = 1e-3 / metres_per_unit(unit);
  VesselScale s;
  s.large_radius = large * per_mm;
  s.median_radius = median * per_mm;
  s.small_radius = small * per_mm;
  s.extent = extent * per_mm;
  s.label_array = std::move(labels);
  return s;
}

TEST(Units, GivenUnitsAreKept) {
  for (LengthUnit u : {LengthUnit::kMm, LengthUnit::kCm, LengthUnit::kM}) {
    const ModelUnit m = decide_unit(u, in_unit(1, 1, 1, 50, LengthUnit::kM));
    EXPECT_EQ(m.unit, u);
    EXPECT_FALSE(m.guessed);
    EXPECT_TRUE(m.certain);
    EXPECT_EQ(m.alternative, LengthUnit::kGuess);
    EXPECT_EQ(parse_unit(unit_symbol(u)), u);
    EXPECT_EQ(unit_summary(m), std::string(unit_symbol(u)) + " (given)");
  }
  EXPECT_EQ(parse_unit("inch"), LengthUnit::kGuess);
  EXPECT_DOUBLE_EQ(metres_per_unit(LengthUnit::kCm) / metres_per_unit(LengthUnit::kMm), 10);
}

// Human vessels of textbook sizes (mm: largest, median and smallest radius,
// bounding-box diagonal), written in each unit: the true unit is never
// ruled out (it is the guess, or the alternative the guess names), and a
// certain guess is the true one.
TEST(Units, TheTrueUnitIsTheGuessOrItsAlternative) {
  struct Model {
    const char* what;
    double large, median, small, extent;
  };
  const Model models[] = {
      {"thoracic aorta", 15, 12, 6, 350},     {"abdominal aorta and iliacs", 10, 8, 4, 250},
      {"carotid bifurcation", 3.5, 3, 2, 70}, {"coronary tree", 2, 1.3, 0.7, 120},
      {"cerebral aneurysm", 3, 1.8, 1, 40},   {"femoral artery", 4, 3.5, 3, 200}};
  for (const Model& m : models)
    for (LengthUnit truth : {LengthUnit::kMm, LengthUnit::kCm, LengthUnit::kM}) {
      const ModelUnit u =
          decide_unit(LengthUnit::kGuess, in_unit(m.large, m.median, m.small, m.extent, truth));
      SCOPED_TRACE(std::string(m.what) + " in " + std::string(unit_symbol(truth)) + ": " +
                   unit_summary(u));
      EXPECT_TRUE(u.guessed);
      EXPECT_TRUE(u.unit == truth || u.alternative == truth);
      if (u.certain) {
        EXPECT_EQ(u.unit, truth);
      }
      EXPECT_EQ(u.certain, u.confidence == UnitConfidence::kCertain);
      EXPECT_EQ(u.certain, u.alternative == LengthUnit::kGuess);
    }
}

TEST(Units, AortasAndMetresAreCertainSmallVesselsNot) {
  // An aorta in mm would be 12 cm wide in cm: only mm fits.
  ModelUnit aorta = decide_unit(LengthUnit::kGuess, in_unit(12, 10, 5, 300, LengthUnit::kMm));
  EXPECT_EQ(aorta.unit, LengthUnit::kMm);
  EXPECT_TRUE(aorta.certain);
  // Any vessel written in metres is certain: mm and cm would be too small.
  ModelUnit carotid = decide_unit(LengthUnit::kGuess, in_unit(3.5, 3, 2, 70, LengthUnit::kM));
  EXPECT_EQ(carotid.unit, LengthUnit::kM);
  EXPECT_TRUE(carotid.certain);
  EXPECT_NE(carotid.reason.find("0.0035 largest"), std::string::npos) << carotid.reason;
  EXPECT_NE(unit_summary(carotid).find("m (guessed, certain: "), std::string::npos);
  // A small vessel in mm could be a large one in cm: never certain, and
  // the question names the other unit.
  ModelUnit coronary = decide_unit(LengthUnit::kGuess, in_unit(2, 1.3, 0.7, 120, LengthUnit::kMm));
  EXPECT_EQ(coronary.unit, LengthUnit::kMm);
  EXPECT_FALSE(coronary.certain);
  EXPECT_EQ(coronary.alternative, LengthUnit::kCm);
  EXPECT_NE(unit_summary(coronary).find("; if it is cm, say {units} cm)"), std::string::npos)
      << unit_summary(coronary);
}

TEST(Units, FaceLabelsPickCentimetresAmongUnitsThatFitAsWell) {
  // 12 mm in cm or 1.2 mm in mm: both human vessel sizes.
  const VesselScale s = in_unit(12, 9, 6, 300, LengthUnit::kCm);
  VesselScale labelled = s;
  labelled.label_array = "ModelFaceID";
  const ModelUnit plain = decide_unit(LengthUnit::kGuess, s);
  const ModelUnit simvascular = decide_unit(LengthUnit::kGuess, labelled);
  EXPECT_EQ(simvascular.unit, LengthUnit::kCm);
  EXPECT_EQ(simvascular.confidence, UnitConfidence::kUnsure);
  EXPECT_EQ(simvascular.alternative, LengthUnit::kMm);
  EXPECT_NE(simvascular.reason.find("face labels (ModelFaceID) hint at cm"), std::string::npos)
      << simvascular.reason;
  EXPECT_EQ(plain.confidence, UnitConfidence::kUnsure);
  // The labels never overrule the sizes: an aorta of 12 mm written in mm
  // stays mm, labels or not.
  VesselScale aorta = in_unit(12, 10, 5, 300, LengthUnit::kMm);
  aorta.label_array = "ModelFaceID";
  EXPECT_EQ(decide_unit(LengthUnit::kGuess, aorta).unit, LengthUnit::kMm);
}

TEST(Units, NoHumanSizeIsUnsureAndSaysSo) {
  // A 5 km "vessel": no unit makes it anatomical.
  const ModelUnit u = decide_unit(LengthUnit::kGuess, in_unit(5e6, 5e6, 5e6, 1e8, LengthUnit::kMm));
  EXPECT_EQ(u.confidence, UnitConfidence::kUnsure);
  EXPECT_NE(u.reason.find("no unit gives human vessel sizes"), std::string::npos) << u.reason;
  // Nothing measured but the extent: weighed on it alone.
  VesselScale box;
  box.extent = 0.08;
  EXPECT_EQ(decide_unit(LengthUnit::kGuess, box).unit, LengthUnit::kM);
  EXPECT_NE(decide_unit(LengthUnit::kGuess, box).reason.find("no vessel radius measured"),
            std::string::npos);
}

TEST(Units, ThePhantomsScaleIsMeasuredAcrossItsLumen) {
  // The bifurcation's parent has radius 1 (0.95 at the split), its
  // branches 0.78 and 0.66 tapering by 0.08 and 0.06.
  PhantomTruth truth;
  PhantomOptions o;
  o.kind = PhantomKind::kBifurcation;
  o.voxel = 0.12;
  o.scale = 3.5;
  const SurfaceMesh m = testing::phantom(o, &truth);
  const VesselScale s = measure_vessel_scale(m, true, truth.opening_radii, "");
  EXPECT_NEAR(s.large_radius, 1.0 * o.scale, 0.15 * o.scale);
  EXPECT_LE(s.small_radius, s.median_radius);
  EXPECT_LE(s.median_radius, s.large_radius);
  EXPECT_GE(s.small_radius, 0.5 * o.scale);
  EXPECT_NEAR(s.smallest_opening, 0.6 * o.scale, 0.05 * o.scale);
  EXPECT_DOUBLE_EQ(s.extent, bounding_box(m.points).diagonal());
  EXPECT_GT(s.enclosed_share, 0.9);
  // Not oriented: the radii come from the openings.
  const VesselScale openings = measure_vessel_scale(m, false, truth.opening_radii, "");
  EXPECT_EQ(openings.enclosed_share, -1);
  EXPECT_NEAR(openings.large_radius, 1.0 * o.scale, 0.1 * o.scale);
  // As a carotid in mm (3.5 mm): mm; the same model a tenth as large is a
  // 3.5 mm carotid written in cm.
  EXPECT_EQ(decide_unit(LengthUnit::kGuess, s).unit, LengthUnit::kMm);
  o.scale = 0.35;
  const SurfaceMesh small = testing::phantom(o, &truth);
  const ModelUnit cm =
      decide_unit(LengthUnit::kGuess, measure_vessel_scale(small, true, truth.opening_radii, ""));
  EXPECT_EQ(cm.unit, LengthUnit::kCm) << cm.reason;
  EXPECT_EQ(cm.alternative, LengthUnit::kMm) << cm.reason;
}

TEST(Units, ASheetEnclosesNothing) {
  // A flat disk: no inward chord meets the surface again.
  SurfaceMesh disk;
  disk.points = {0, 0, 0};
  const int n = 24;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    disk.points.insert(disk.points.end(), {10 * std::cos(a), 10 * std::sin(a), 0});
  }
  for (int i = 0; i < n; ++i)
    disk.triangles.insert(disk.triangles.end(), {0, 1 + i, 1 + (i + 1) % n});
  const VesselScale s = measure_vessel_scale(disk, true, std::vector<double>{10.0}, "");
  EXPECT_EQ(s.enclosed_share, 0);
  EXPECT_EQ(s.open_example, (Vec3{0, 0, 0}));
}

}  // namespace
}  // namespace vm
