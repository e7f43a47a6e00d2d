// The whole job: a surface file's bytes and options in, the meshed result
// and its report out (write_outputs.h writes its files): preparation,
// surface remeshing by conformal maps, boundary layers, caps, volume.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/msh_writer.h"
#include "core/io/output_file.h"
#include "core/layers/first_layer_yplus.h"
#include "core/layers/layer_mesh.h"
#include "core/mesh/volume_mesh.h"
#include "core/pipeline/element_budget.h"
#include "core/pipeline/prepare_surface.h"
#include "core/quality/surface_group_quality.h"
#include "core/surface/cap_openings.h"
#include "core/surface/remesh_surface.h"
#include "core/util/progress.h"
#include "core/util/result.h"

namespace vm {

/// The vessel wall's default spec: 0.1 R in 4 layers, off (layers = 0)
/// until a thickness is asked for.
inline LayerSpec no_vessel_wall() {
  LayerSpec s;
  s.layers = 0;
  s.thickness_fraction = 0.1;
  return s;
}

/// How a mesh family's boundary layer follows its sizes (mesh_family.h):
/// refined with them (the first layer divided by r^k, more layers of the
/// same total thickness), or fixed at the first member's (one first-layer
/// height in every member: the y+ choice).
enum class FamilyLayers { kRefine, kFixed };

/// The solver a mesh is for (solver_preset.h): kNone, no preset.
enum class Solver { kNone, kGmsh, kOpenFoam, kFenics, kSvFsi };

/// One setting of a solver preset as applied: the option's id, its value's
/// text, and whether the preset set it (false: the user gave the option,
/// and the user's value was kept).
struct PresetSetting {
  std::string id, value;
  bool from_preset = true;
};

/// The preset applied to a job (solver_preset.h apply_options): the
/// solver's name ("" = none), what it set, and a note on what the solver
/// needs beyond the file (e.g. a patch type to set after conversion).
struct PresetOutcome {
  std::string solver;
  std::vector<PresetSetting> settings;
  std::string note;
};

struct MeshJobOptions {
  PrepareOptions prepare;
  /// The solver the mesh is for; its preset's defaults are applied by
  /// apply_options (solver_preset.h), which records them in `preset`
  /// (copied to the result for the report).
  Solver solver = Solver::kNone;
  PresetOutcome preset;
  /// How the result is to be written (write_outputs.h; the job itself
  /// writes nothing): the format (none: from the output's file name, else
  /// MSH), the MSH version and file type (binary: 4.1 only), zlib for the
  /// VTK files' arrays, the OpenFOAM case's lists in binary, the unit.
  std::optional<OutputFormat> format;
  MshVersion msh_version = MshVersion::k41;
  bool msh_binary = false;
  bool vtk_compress = false;
  bool foam_binary = false;
  /// Remesh the surface (else the repaired input surface is used).
  bool remesh = true;
  RemeshOptions remesh_options;
  /// Mesh the volume: caps on the openings and tetrahedra inside (else only
  /// the wall surface is written).
  bool volume = true;
  /// Names of openings: (index into the prepared surface's openings, as the
  /// analysis lists them, name). Others are named after the file's face
  /// names, else inlet / outlet_k.
  std::vector<std::pair<int, std::string>> opening_names;
  /// The unit of the written mesh (kGuess: the input's).
  LengthUnit output_units = LengthUnit::kGuess;
  /// Which opening becomes `inlet`: an index into the input's openings as
  /// `vesselmesh info` lists them (largest first); 0 = the largest.
  int inlet = 0;
  /// Target edge length in the core of the lumen; 0: the field's own, i.e.
  /// the uniform size in uniform mode, else grown from the wall's size by
  /// the gradation.
  double core_size = 0;
  /// Boundary layers (seed 2.2): the viscous layer grown inward from the
  /// wall (layers = 0: none) and the vessel wall grown outward (layers = 0,
  /// the default: none); `outward` is set by the job. Defaults: 4 layers of
  /// 0.2 R in all inward; for the wall, 4 layers of 0.1 R when asked.
  LayerSpec viscous;
  LayerSpec vessel = no_vessel_wall();
  /// Whether the vessel wall's thickness was given (a wall asked for by its
  /// number of layers alone is said in a warning).
  bool wall_thickness_given = false;
  /// The first layer's height from a target y+ (yplus.yplus > 0) and the
  /// flow at the inlet (first_layer_yplus.h): set when the surface is known
  /// (the inlet's diameter, the model's unit); refused together with
  /// viscous.first_height.
  YPlusTarget yplus;
  /// The viscous layer as its own volume `boundary_layer` (else in `lumen`).
  bool tag_layer = false;
  /// Keep the layers' prisms (MSH type 6; their faces at the openings as
  /// quads, type 3) instead of splitting them into tetrahedra.
  bool keep_prisms = false;
  /// The element budget: a job whose wall triangles or tetrahedra are
  /// estimated beyond it is refused before meshing them, unless its size is
  /// the default: that is coarsened to fit (element_budget.h).
  double max_elements = 15e6;
  /// The memory the job may take, in bytes (0: no limit): set by the
  /// WebAssembly binding to what its module can still grow by. A size whose
  /// tetrahedra, at kWasmBytesPerTetrahedron each, need more is refused
  /// before meshing (the default size coarsened) as the element budget is;
  /// not an option of the table: a property of where the job runs.
  double memory_bytes = 0;
  /// Whether the wall's size was given ({size} or {per_circumference}).
  bool size_given = false;
  /// The remeshed wall may enclose at most this fraction more or less
  /// volume than its input; beyond, the size is refused as too coarse.
  double max_volume_change = 0.05;
  /// Check the volume mesh fully before writing it (conformity, boundary =
  /// surface triangles), not only that no element is inverted.
  bool verify = false;
  /// Threads the loops use (set_thread_count, core/util/parallel.h): 0 all
  /// cores. The output is the same with any number.
  int threads = 0;
  /// A mesh-independence family (mesh_family.h): this many meshes, member k
  /// with its sizes divided by family_ratio^k (1: one mesh), its boundary
  /// layer per family_layers.
  int family = 1;
  double family_ratio = 1.4;
  FamilyLayers family_layers = FamilyLayers::kRefine;
  /// The volume's size gradation is divided by this (a family member's
  /// r^k, so that its field is the first member's scaled; not an option).
  double gradation_divisor = 1;
};

/// Counts and timings of the volume stages.
struct VolumeStats {
  /// Volume of the lumen (core and viscous layer; the vessel wall apart),
  /// model units cubed: the sum of its elements' volumes.
  double lumen_volume = 0;
  LayerStats boundary_layer, vessel_wall;   ///< when grown
  int viscous_layers = 0, wall_layers = 0;  ///< layers grown (0: none)
  size_t front_steiner_points = 0;          ///< recovery's points on the layer front
  size_t steiner_points = 0;                ///< added on the surface by boundary recovery
  /// Of the front's, those the viscous layer's top slice took (the wall
  /// keeps its triangles).
  size_t absorbed_steiner_points = 0;
  /// Recovery's points that split wall triangles (on a wall without a
  /// viscous layer, or carried down the layers' columns), and of those the
  /// ones moved along their edge to better the wall's triangles.
  size_t wall_steiner_points = 0, reoptimized_steiner_points = 0;
  /// Missing edges recovered by flips along the edge that would otherwise
  /// each have had a Steiner point.
  size_t edges_recovered_by_flips = 0;
  /// Wall edges recovery flipped on the wall instead of splitting them
  /// (wall_flip_rule, core/layers/flip_wall_edges.h).
  size_t wall_edges_flipped = 0;
  /// Where the wall changed: the flipped edges' midpoints, then the points
  /// that split it (model units).
  std::vector<std::array<double, 3>> wall_change_places;
  size_t inserted_points = 0;  ///< added inside by refinement
  double seconds_layers = 0, seconds_caps = 0, seconds_recovery = 0, seconds_refinement = 0,
         seconds_assembly = 0, seconds_check = 0;
  /// Parts of seconds_refinement: point insertion, and the optimization.
  double seconds_fill_refine = 0, seconds_fill_optimize = 0;
};

/// How faithful the remeshed surface is to its input.
struct SurfaceFidelity {
  /// Largest distance of an output vertex to the input surface, relative to
  /// the input's bounding-box diagonal (0 up to rounding: vertices lie on it).
  double max_vertex_offset = 0;
  /// Largest distance of an input vertex to the output surface, relative to
  /// the target size h at that vertex (how much detail the size discards).
  double max_input_gap = 0;
  /// Input vertices farther than 0.1 h from the output surface.
  size_t input_gap_vertices = 0;
  /// Pairs of output triangles that intersect (0 for a valid surface).
  size_t self_intersections = 0;
  /// Volumes enclosed by the input and the remeshed wall, each opening
  /// closed by a fan (model units cubed), and the relative change.
  double input_volume = 0, output_volume = 0, volume_change = 0;
};

/// One physical group of the written file and its element count.
struct OutputGroup {
  int dim = 2;
  int tag = 1;  ///< its physical tag, unique across dimensions (write_outputs.h physical_tags)
  std::string name;
  size_t elements = 0;
};

/// The first layer's height as set from a target y+.
struct FirstLayerFromYPlus {
  YPlusTarget target;         ///< the y+ and the flow (SI)
  YPlusHeight estimate;       ///< Re, Cf, tau_w, u_tau, the height in metres
  std::string inlet;          ///< the group name of the opening used
  double inlet_diameter = 0;  ///< its equivalent diameter 2 sqrt(area / pi), model unit
  double height = 0;          ///< the first layer's height, model unit
};

struct MeshJobResult {
  PreparedSurface surface;  ///< the input as read and analyzed
  PresetOutcome preset;     ///< the solver preset applied (options.preset)
  /// When the first layer's height came from a target y+.
  std::optional<FirstLayerFromYPlus> first_layer_yplus;
  SurfaceMesh output_surface;         ///< the surface written (wall)
  std::vector<float> output_quality;  ///< gamma_k per output triangle
  QualityStats output_quality_stats;
  std::vector<OutputGroup> groups;  ///< physical groups of the files (output_groups)
  bool remeshed = false;
  RemeshStats remesh_stats;        ///< when remeshed
  TopologyReport output_topology;  ///< when remeshed (checked equal to the input's)
  SurfaceFidelity fidelity;        ///< when remeshed
  /// The default size coarsened to fit the element budget (when remeshed).
  BudgetFit budget;
  /// When the volume was meshed: the closed surface (wall + caps) and the
  /// volume mesh (tets, region 0 = lumen; its triangles are the surface as
  /// written, with one tag per triangle: 0 wall, i inlet/outlets as caps).
  CappedSurface capped;
  VolumeMesh volume;
  /// The group name of each opening of `surface` (its analysis order).
  std::vector<std::string> opening_names;
  std::vector<std::string> surface_names;  ///< per triangle tag ("" = unused tag)
  std::vector<std::string> region_names;   ///< per tet region ("" = unused region)
  /// gamma_k of the surfaces as written, per group (the wall after
  /// recovery; caps' discs and layer rings apart).
  std::vector<SurfaceGroupQuality> written_quality;
  std::vector<float> tet_quality;  ///< gamma_t per tetrahedron
  QualityStats tet_quality_stats;  ///< of all the tetrahedra
  /// Of the core's tetrahedra only (the isotropic part; layer elements are
  /// flat by design).
  QualityStats core_quality_stats;
  /// Per tetrahedron, the part it belongs to whatever the groups: 0 the
  /// core, 1 the viscous layer, 2 the vessel wall.
  std::vector<uint8_t> tet_part;
  VolumeStats volume_stats;
  std::vector<std::string> warnings;
  double seconds_total = 0;
};

/// The element budget `options` set (element_budget.h).
ElementBudget element_budget(const MeshJobOptions& options);

/// The error of a job that ran out of memory during `stage` (a progress
/// stage's name, "" before the first) at `fraction` of its progress.
Status out_of_memory_error(std::string_view stage, double fraction);

/// Meshes the surface file `file_bytes` per `options`. `input_read`, if
/// given, is called once the bytes are no longer needed (after the
/// preparation), so that the caller may free them before the later stages
/// (a 25M-triangle binary STL is 1.25 GB). An allocation that fails
/// (std::bad_alloc, here or on a worker thread) ends the job with an error
/// saying which stage ran out of memory (out_of_memory_error); where C++
/// exceptions are not caught (the WebAssembly build), the module aborts
/// instead and the JS API says so.
Result<MeshJobResult> run_mesh_job(std::span<const uint8_t> file_bytes,
                                   const MeshJobOptions& options = {},
                                   const ProgressFn& progress = {},
                                   const std::function<void()>& input_read = {});

/// The job after its preparation (stage 1), on a surface prepare_surface
/// made with options.prepare: what run_mesh_job does once the file is read.
/// An opening cut deeper for the layer (cut_openings_deeper) is cut in the
/// result's `surface`. seconds_total counts from here.
Result<MeshJobResult> run_mesh_job_on(PreparedSurface surface, const MeshJobOptions& options,
                                      const ProgressFn& progress = {});

}  // namespace vm
