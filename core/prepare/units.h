// The length unit of a model: the file's numbers carry none, so the user
// says it (--units) or it is guessed from the model's scale weighed against
// human anatomy (our own method; the ranges and their sources are at
// decide_unit). The scale is measured once per file, on the repaired
// surface before smoothing, cap removal, cuts and flow extensions, so that
// none of those options can change the guess.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "core/geom/vec3.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

enum class LengthUnit { kGuess, kMm, kCm, kM };

/// "mm", "cm", "m" ("" for kGuess).
std::string_view unit_symbol(LengthUnit unit);
/// Metres per unit (0 for kGuess).
double metres_per_unit(LengthUnit unit);

/// How sure a guessed unit is: kCertain, no other unit gives human vessel
/// sizes; kLikely, another does but only unusual ones; kUnsure, another
/// gives sizes as typical (or none gives human sizes at all).
enum class UnitConfidence { kCertain, kLikely, kUnsure };

/// "certain", "likely", "unsure".
std::string_view confidence_name(UnitConfidence confidence);

/// The scale of a model in its file's numbers: what the unit guess weighs.
struct VesselScale {
  /// The vessel radius at the wall as half the chord across the lumen along
  /// the inward normal (half_chords of core/mesh/chord_radius.h, at up to
  /// kScaleSamples vertices), as area-weighted percentiles: the 90th stands
  /// for the largest vessel, the 50th for the median one, the 10th for the
  /// smallest; all 0 when nothing was measured. Without a chord (a surface
  /// not oriented) they come from the openings' radii.
  double large_radius = 0, median_radius = 0, small_radius = 0;
  /// The smallest radius of an opening of the file (holes excluded) of at
  /// least a tenth of large_radius (smaller ones are defects rather than
  /// vessels cut by the modeller); 0 when none.
  double smallest_opening = 0;
  /// The bounding box's diagonal.
  double extent = 0;
  /// The file's face label array ("ModelFaceID", ...; "" none): SimVascular
  /// and VMTK write one, and SimVascular models are usually in centimetres.
  std::string label_array;
  /// The share of the sampled wall area whose inward chord meets the wall
  /// again: near 1 for a vessel (a closed lumen or a tube cut open; rays
  /// leave only through openings), near 0 for a single sheet that encloses
  /// no volume (a flat disk, one side of a wall); -1 when no chord was cast
  /// (not oriented, or empty).
  double enclosed_share = -1;
  /// A sampled vertex whose inward chord meets nothing (the first found).
  Vec3 open_example{};
  /// The smallest vessel radius weighed: small_radius, or the smallest
  /// opening when smaller.
  double smallest() const;
  bool measured() const { return large_radius > 0; }
};

/// Vertices at most whose half chords measure the scale (a stride through
/// the vertices beyond): the percentiles agree with every vertex's to 1% on
/// real models, at a few milliseconds.
inline constexpr size_t kScaleSamples = 20000;

/// Measures `mesh` (any size; nothing measured on an empty one). Its
/// chords only when `oriented` (consistently, outward), else the radii come
/// from the openings. `opening_radii`: the radii of its openings that are no
/// holes (any order; 0 entries are ignored).
VesselScale measure_vessel_scale(const SurfaceMesh& mesh, bool oriented,
                                 std::span<const double> opening_radii, std::string label_array);

/// The unit of a model and how it was decided.
struct ModelUnit {
  LengthUnit unit = LengthUnit::kMm;
  bool guessed = false;  ///< not given by the user
  /// For a guess: what it rests on, in words ("vessel radius 1.57 largest,
  /// ...; cm gives typical human vessel sizes, mm ...").
  std::string reason;
  /// confidence == kCertain (a given unit is certain).
  bool certain = true;
  UnitConfidence confidence = UnitConfidence::kCertain;
  /// For a guess that is not certain: the next unit that gives human vessel
  /// sizes (kGuess: none).
  LengthUnit alternative = LengthUnit::kGuess;
};

/// The user's unit when given, else the guess from `scale`: each of mm, cm
/// and m turns the measures into millimetres, and each measure is typical,
/// possible or impossible for human vessels (the ranges below); a unit is
/// as good as its worst measure. The best unit wins; among equals the face
/// labels pick cm, then the unit nearest the typical sizes (the smallest sum
/// of squared logarithmic distances to each typical range's geometric
/// centre) wins.
///
/// Ranges (mm; typical, then possible):
///   largest vessel radius  1-20,    0.3-40: from a major cerebral or
///     coronary artery (MCA M1 1.2-1.5, LAD 1.5-2) to the aortic root
///     (14-18); down to small-animal or distal segments, up to aneurysmal
///     aortas (AAA to 80 diameter) and giant aneurysms;
///   median vessel radius   0.5-15,  0.2-35: the same vessels by area;
///   smallest vessel radius 0.35-15, 0.08-30: clinical CT/MR angiography
///     has voxels of 0.3-0.8 and resolves vessels of about 2 voxels across
///     (3D rotational angiography, 0.1-0.2, some smaller);
///   bounding-box diagonal  10-700,  3-2000: from a cerebral bifurcation
///     or coronary segment to the aorta with its iliacs (500-600), up to a
///     whole-body arterial tree.
/// Sources: textbook adult lumen diameters (aortic root about 30-36, an
/// abdominal aortic aneurysm from 30: ESC 2014 guidelines on aortic
/// diseases; carotid 6-8, coronary 1-5, cerebral 2-3), and the voxel sizes
/// of clinical angiography protocols. Not meant for animal models.
ModelUnit decide_unit(LengthUnit asked, const VesselScale& scale);

/// The unit in one line, options as {option_id} (phrase_options): "mm
/// (given)", "m (guessed, certain: REASON)", "cm (guessed, likely: REASON;
/// if it is mm, say {units} mm)".
std::string unit_summary(const ModelUnit& unit);

}  // namespace vm
