// Stage 1 of the pipeline: read a surface file, weld, repair and analyze it.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/io/read_surface.h"
#include "core/io/stl.h"
#include "core/mesh/manifold_repair.h"
#include "core/mesh/repair.h"
#include "core/mesh/self_crossings.h"
#include "core/mesh/surface_mesh.h"
#include "core/mesh/topology.h"
#include "core/mesh/weld.h"
#include "core/prepare/clip_surface.h"
#include "core/prepare/recognize_caps.h"
#include "core/prepare/resurface_crossings.h"
#include "core/prepare/smooth_surface.h"
#include "core/prepare/trim_damaged_ends.h"
#include "core/prepare/units.h"
#include "core/prepare/vessel_ends.h"
#include "core/quality/triangle_quality.h"
#include "core/util/progress.h"
#include "core/util/result.h"

namespace vm {

struct PrepareOptions {
  StlReadOptions read;
  WeldOptions weld;
  /// Keep only the largest connected component (the others are removed
  /// and reported) instead of refusing inputs with several components.
  bool largest_component_only = false;
  /// Repair of dirty surfaces (phase 2): non-manifold edges and vertices
  /// split into manifold sheets, and holes smaller than hole_fraction of
  /// the local vessel radius closed. False: only the safe repairs (zero-area
  /// and duplicate triangles, orientation); holes are listed, not closed.
  bool repair = true;
  double hole_fraction = 0.25;
  /// Flow extensions, in local radii of each opening (0: none): the length
  /// for every opening, then per opening (index in the analysis' order,
  /// before extension) where given.
  double flow_extension = 0;
  std::vector<std::pair<int, double>> flow_extensions;
  /// Smoothing before cap recognition: kAuto smooths voxel staircases only
  /// (detected by their facet normals), a count of passes smooths any
  /// surface, kOff never.
  Smoothing smoothing;
  /// Clipping after cap recognition: by the given planes (each removes the
  /// side its normal points to), across the vessels at the given points,
  /// then at the blind vessel ends left (clip_auto, clip_distance local
  /// radii in from each tip), whether the surface is closed or has
  /// openings already. Without clip_auto the blind ends are kept and
  /// proposed (clip_proposals).
  bool clip_auto = true;
  double clip_distance = 1;
  std::vector<ClipPlane> clip_planes;
  /// ... and across the vessel at the surface points nearest these (model
  /// coordinates), removing the side with less surface.
  std::vector<std::array<double, 3>> clip_at;
  /// Keep planar caps as part of the wall (else each recognised cap is
  /// removed and its rim becomes an opening).
  bool keep_caps = false;
  CapRecognitionOptions caps;
  /// The unit of the file's numbers; kGuess: guessed from the vessel radii.
  LengthUnit units = LengthUnit::kGuess;
  int histogram_bins = 20;
};

/// Where an opening of the prepared surface comes from.
struct OpeningSource {
  /// Open in the file, a recognised cap removed, a cut made by clipping.
  enum Kind { kFile, kCap, kClip } kind = kFile;
  int32_t label = -1;  ///< a cap's face label, or -1
  std::string name;    ///< a cap's name in the file, or ""
  /// Length of the flow extension added at this opening (model units; 0:
  /// none): the opening is then the extension's circular end.
  double extension = 0;
  /// What was opened: a cap's shape (labelled, planar, fan, dome: the fans
  /// and domes are cut at their rim's best-fit plane), or what a cut was
  /// made at (a blind vessel end by {clip} auto, a plane given, a point
  /// given, a damaged end trimmed by {repair} auto); kNone for an opening
  /// of the file.
  enum Shape {
    kNone,
    kLabelled,
    kPlanar,
    kFan,
    kDome,
    kBlindEnd,
    kPlane,
    kPoint,
    kDamagedEnd
  } shape = kNone;
};

/// "file", "cap", "clip".
inline const char* opening_source_name(OpeningSource::Kind kind) {
  return kind == OpeningSource::kCap ? "cap" : kind == OpeningSource::kClip ? "clip" : "file";
}

/// "" (kNone), "labelled", "planar", "fan", "dome", "blind_end", "plane",
/// "point", "damaged_end".
const char* opening_shape_name(OpeningSource::Shape shape);

/// A boundary loop too small to be an opening: a defect of the surface.
struct Hole {
  double perimeter = 0;  ///< model units
  double radius = 0;     ///< sqrt(area / pi) of the loop closed by a fan
  Vec3 centroid{};
  /// The local vessel radius it was compared with: the median over the
  /// loop's vertices of the half chord across the lumen (chord_radius).
  double vessel_radius = 0;
  bool closed = false;  ///< filled (else it is still an opening of `topology`)
  size_t triangles_added = 0;
  double min_angle = 0;  ///< of the fill's triangles, degrees
};

/// Phase 4's outcome: what the surface was found to be and how it was
/// smoothed.
struct SmoothingOutcome {
  Smoothing::Mode mode = Smoothing::Mode::kAuto;  ///< as asked
  StaircaseReport staircase;                      ///< detection (every mode)
  bool applied = false;                           ///< vertices were moved
  /// The clamp's voxel (model units): the staircase's largest voxel side,
  /// or, smoothing a surface that is not one, its median edge length.
  double voxel = 0;
  SmoothReport report;  ///< when applied
};

/// The welded, repaired surface and everything known about it.
struct PreparedSurface {
  SurfaceMesh mesh;
  bool ascii = false;          ///< ASCII STL
  std::string format;          ///< what was read (SurfaceFile::format), e.g. "binary STL"
  size_t input_triangles = 0;  ///< triangles in the file
  WeldStats weld;
  RepairStats repair;
  bool repaired = true;  ///< phase 2 ran with {repair} auto
  ManifoldRepairStats manifold;
  /// Where the file's surface crossed itself and was re-surfaced (phase 2,
  /// {repair} auto), place by place.
  ResurfaceReport resurfaced;
  /// Damaged vessel ends found (phase 2, {repair} auto): trimmed back to a
  /// clean cross-section (its cut made in phase 6), or left when the damage
  /// reaches too deep.
  std::vector<TrimmedEnd> trimmed_ends;
  /// Boundary loops found smaller than {hole_fraction} of the local vessel
  /// radius, in the order found (by decreasing radius), closed or not.
  std::vector<Hole> holes;
  TopologyReport topology;
  BoundingBox box;
  std::vector<float> quality;  ///< gamma_k per triangle of `mesh`
  QualityStats quality_stats;
  /// The face label array the file had ("ModelFaceID", ...; "" for none).
  std::string label_array;
  /// One per opening of `topology` (same order).
  std::vector<OpeningSource> opening_sources;
  size_t caps_removed = 0;
  SmoothingOutcome smoothing;
  /// The cuts made by clipping, in order (each is an opening of source
  /// "clip" unless a later cut removed it).
  std::vector<ClipCut> clips;
  /// Separate pieces under 1% of the largest (triangles or area) removed.
  size_t specks_removed = 0;
  /// A surface not clipped ({clip} off): the cuts {clip} auto would make,
  /// one per blind vessel end found.
  std::vector<VesselEnd> clip_proposals;
  /// The model's scale, measured on the repaired surface before smoothing,
  /// caps, cuts and flow extensions (measure_vessel_scale), and the length
  /// unit given or guessed from it.
  VesselScale scale;
  ModelUnit unit;
  /// Where the prepared surface crosses itself (a wall pushed through
  /// another): found on surfaces up to kSelfCrossingCheckLimit triangles,
  /// else not looked for (self_crossings_checked false).
  SelfCrossings self_crossings;
  bool self_crossings_checked = false;
  /// Human-readable notes on the safe repairs applied and on properties that
  /// later stages will refuse (non-manifold edges, several components).
  std::vector<std::string> warnings;
};

/// The largest surface whose self-crossings preparation looks for: the
/// search costs about a quarter of the preparation's time at any size (2.5 s
/// at 2M triangles) and ~60 bytes a triangle, so larger ones are skipped.
inline constexpr size_t kSelfCrossingCheckLimit = 2'000'000;

/// "the input crosses itself at (x, y, z) UNIT (N places; what to do): ", or "" when the
/// surface was not found crossing itself: the prefix of a later stage's
/// error on such a surface.
std::string self_crossing_prefix(const PreparedSurface& surface);

/// Reads a surface file's bytes (any format read_surface reads) and
/// prepares the surface. Errors are the reader's, or "no triangle left"
/// when every triangle was degenerate.
Result<PreparedSurface> prepare_surface(std::span<const uint8_t> file_bytes,
                                        const PrepareOptions& options = {},
                                        const ProgressFn& progress = {});

/// Cuts each opening nearest one of `places` (model units; e.g. where the
/// boundary layer met the opening's plane at a grazing angle) again,
/// `depth` of its radii deeper into the vessel, parallel to it, and
/// analyzes the surface again (openings, their sources, self-crossings,
/// quality), with a warning per cut. Errors: no opening, or a cut that
/// fails (clip_surface's errors).
Status cut_openings_deeper(PreparedSurface& surface, const std::vector<Vec3>& places,
                           double depth);

/// Checks that a prepared surface can be meshed: manifold, orientable, one
/// component. The error message says what is wrong, where, and what to do.
Status check_meshable(const PreparedSurface& surface);

}  // namespace vm
