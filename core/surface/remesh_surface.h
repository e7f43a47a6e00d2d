// Whole-surface remeshing by conformal maps (Marchandise et al., sections
// 2.1 and 3): size field, partition into parametrizable patches, seams
// discretized once, each patch meshed in its parameter plane, assembly,
// optimization on the input surface.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/surface/isotropic_remesh_patch.h"
#include "core/surface/optimize_surface.h"
#include "core/surface/partition.h"
#include "core/surface/remesh_patch.h"
#include "core/surface/size_field.h"
#include "core/util/progress.h"
#include "core/util/result.h"

namespace vm {

/// The map of each patch to the plane (seed Fig. 6).
enum class ParamMethod {
  kLscm,      ///< finite-element least-squares conformal map (default)
  kHarmonic,  ///< harmonic map onto the unit disk
  kFloater,   ///< Floater's mean-value map onto the unit disk
};

struct RemeshOptions {
  SizeOptions size;
  /// R per input vertex (vessel_radius) when the caller has it, for the
  /// per-circumference sizes; else (empty) computed here.
  std::span<const double> radius;
  ParamMethod param = ParamMethod::kLscm;
  PatchMeshOptions patch;  ///< 2D mesher and its options
  PartitionOptions partition;
  SurfaceOptimizeOptions optimize;
  /// Creases sharper than this (angle between the normals of two triangles,
  /// degrees) that form closed or anchored chains are kept: patches end at
  /// them and their vertices stay on them. 180 = off.
  double feature_angle_degrees = 60;
  /// Fidelity: input vertices farther than this times h from the output
  /// get an output vertex pinned onto them (pin_to_input), then the mesh is
  /// optimized around them again, at most `fidelity_rounds` times (0: off).
  double fidelity = 0.1;
  int fidelity_rounds = 5;
  /// Pinning is not tried when more input vertices than this share of
  /// the output's vertices are far (noise everywhere).
  double fidelity_max_share = 0.3;
  /// Size rounds: when input vertices are left beyond fidelity h, and at
  /// most fidelity_noise_share of the output's vertices (beyond that they
  /// are noise, smoothed over), the size is made finer within h of each (a
  /// chord's gap grows as h^2: by the square root of the gap's excess,
  /// 0.5 to 0.9 times per round, graded) and the surface meshed again, at
  /// most this many times, from the last round's sizes. The limit stays
  /// fidelity times the asked h. Rounds stop when the median edge over the
  /// asked size falls below 1 - fidelity_size_drift; the surface kept is
  /// the one with the fewest far vertices. A round remeshes the whole
  /// surface: on outputs of more than fidelity_small_surface vertices,
  /// only when more than fidelity_size_share of them are far.
  int fidelity_size_rounds = 10;
  /// Probe rounds: the wall just meshed (before its optimization) measures
  /// its own gaps to the input; where they are beyond fidelity h (and
  /// worth a size round, see fidelity_size_share), the size is made finer
  /// around them and the wall meshed again, at most this many times, so
  /// that few input vertices are left to pin.
  int fidelity_probe_rounds = 1;
  /// Local size rounds: when the pinning rounds leave input vertices beyond
  /// fidelity h, the size is halved within h of each and the wall split
  /// and relaxed there, then pinned again, at most this many times, before
  /// any size round meshes the whole surface again.
  int fidelity_local_rounds = 2;
  size_t fidelity_small_surface = 30000;
  double fidelity_size_share = 0.0005, fidelity_noise_share = 0.2, fidelity_size_drift = 0.095;
  /// Optimization passes after each fidelity round, in which a pinned
  /// vertex may slide on the input within fidelity_pin_slack times
  /// fidelity h of its input vertex.
  int fidelity_passes = 10;
  double fidelity_pin_slack = 0.8;
  /// Those passes change the wall only within this many rings of what the
  /// round changed (-1: anywhere the passes carry it).
  int fidelity_relax_rings = 2;
  /// Pins left in a triangle with gamma_k below this are freed again
  /// (and given up on), except in fidelity_last_rounds more rounds that
  /// retry every vertex left far with fidelity_last_min_quality (with
  /// fidelity_floor_min on walls of more than fidelity_small_surface
  /// vertices, where no size round may follow).
  double fidelity_min_quality = 0.75;
  int fidelity_last_rounds = 2;
  double fidelity_last_min_quality = 0.6;
  /// After each round the worst and mean gamma_k must stay at least
  /// min(their values before pinning, these floors: the seed's Table 1
  /// frontal row): pins of ever better triangles are freed until they do.
  /// A round that still fails them, or that made a self-intersection or a
  /// needle (a vertex whose star no direction sees), is undone.
  double fidelity_floor_min = 0.55, fidelity_floor_mean = 0.978;
  /// The element budget: a size field that would make more triangles than
  /// this (estimate_triangles) is refused before meshing (0: no limit).
  double max_triangles = 0;
  /// Decimation of an oversampled input before phase 2: when the input has
  /// at least decimate_min_triangles triangles and more than decimate_ratio
  /// times the triangles the size field asks for, edges are collapsed
  /// (decimate_surface) within decimate_error times h of the input's planes
  /// and up to edges of decimate_edge times h; the later phases run on the
  /// decimated surface, whose vertices are then moved onto the input (by
  /// at most about decimate_error h). Off: phases 2-7 on the input as it is.
  bool decimate = true;
  size_t decimate_min_triangles = 200000;
  double decimate_ratio = 8, decimate_error = 0.02, decimate_edge = 0.5;
  /// The patches whose planar meshing fails are split, all at once, and
  /// the surface partitioned again, at most this many times; then a patch
  /// that still fails (or one too small to split) is remeshed on its own
  /// triangles instead (isotropic_remesh_patch, options `fallback`).
  size_t max_splits = 16;
  IsotropicRemeshOptions fallback;
  /// For tests: the patches holding the input triangle nearest each of
  /// these points (model unit) take the fallback without trying their map.
  std::vector<std::array<double, 3>> fallback_at;
};

/// A patch remeshed by the fallback (RemeshOptions::max_splits), for the
/// warnings and the report.
struct FallbackPatch {
  std::array<double, 3> place{};  ///< the mean of its input triangles' corners
  size_t input_triangles = 0;     ///< of the surface the phases ran on
  std::string reason;             ///< why its map could not serve
  size_t splits = 0;              ///< rounds of splits of failed patches before it
  /// The wall's triangles there at the end (those whose centroid lies on
  /// one of its input triangles) and their gamma_k.
  size_t triangles = 0;
  double quality_min = 0, quality_mean = 0;
  double seconds = 0;  ///< meshing it (the failed planar attempt included)
};

/// The input-vertex distance to the output (over h) the statistics count.
inline constexpr double kReportedGap = 0.1;

struct RemeshStats {
  size_t patches = 0;
  size_t bisections = 0;
  size_t rejected_maps = 0;  ///< maps refused (folded or crowded) before splitting
  size_t seam_points = 0;    ///< points on seams and openings, shared by patches
  /// Triangles of the surface the phases ran on when the input was
  /// decimated (else 0).
  size_t decimated_triangles = 0;
  size_t feature_edges = 0;  ///< input edges kept as sharp features
  size_t retries = 0;        ///< partitions redone because patches failed to mesh
  /// Patches remeshed by the fallback, in patch order.
  std::vector<FallbackPatch> fallback_patches;
  size_t swaps = 0, moves = 0, collapses = 0;
  double size_min = 0, size_median = 0, size_max = 0;  ///< of the size field at input vertices
  /// Output edge length / asked size (mean of its ends' sizes, before any
  /// size round): median and 10th / 90th percentiles over the edges (1 =
  /// the field followed exactly).
  double edge_ratio_median = 0, edge_ratio_p10 = 0, edge_ratio_p90 = 0;
  /// Fidelity: pinning rounds done, output vertices pinned, and at the end
  /// the largest input-vertex distance to the output over the asked h,
  /// with the count of input vertices beyond kReportedGap h.
  size_t fidelity_rounds = 0, fidelity_pinned = 0;
  bool fidelity_reverted = false;    ///< a pinning round was undone
  size_t fidelity_size_rounds = 0;   ///< meshings again at a finer size
  size_t fidelity_local_rounds = 0;  ///< local size rounds kept
  double max_input_gap = 0;
  size_t input_gap_vertices = 0;
  /// Pairs of self-intersecting output triangles when the fidelity stage
  /// has counted them exactly (it checks every pinning round against the
  /// surface before it), else -1.
  int64_t self_intersections = -1;
  double seconds_size = 0, seconds_decimate = 0, seconds_partition = 0, seconds_mesh = 0,
         seconds_optimize = 0, seconds_fidelity = 0;
};

/// The remeshed surface, with what ties it to the input.
struct RemeshedSurface {
  SurfaceMesh mesh;
  /// Per output vertex: an input triangle that contains it.
  std::vector<int32_t> home;
  /// Per output vertex: it lies on an opening (boundary loop) of the input.
  std::vector<uint8_t> on_opening;
  /// Per output vertex: it lies on a sharp feature of the input.
  std::vector<uint8_t> on_feature;
  /// The size field at the input vertices.
  std::vector<double> input_sizes;
  /// Per input vertex: its distance to the output surface.
  std::vector<double> input_gaps;
  /// The target size at each output vertex (from its home triangle).
  std::vector<double> sizes;
};

/// The warning for a patch the fallback remeshed: where (in `unit`), why,
/// and the quality there.
std::string fallback_warning(const FallbackPatch& patch, std::string_view unit);

/// Remeshes `input` (one component, manifold, consistently oriented, as
/// prepared by prepare_surface). The output has the same topology (genus,
/// openings), every vertex on the input surface, openings resampled at the
/// target size. A patch whose map or planar mesher keeps failing is
/// remeshed by the fallback (RemeshStats::fallback_patches). Errors:
/// invalid size options, an input that cannot be partitioned into disks,
/// a fallback that fails too, cancellation.
Result<RemeshedSurface> remesh_surface(const SurfaceMesh& input, const RemeshOptions& options = {},
                                       RemeshStats* stats = nullptr,
                                       const ProgressFn& progress = {});

}  // namespace vm
