// A mesh-independence family: N meshes of one surface, systematically
// refined by a ratio r, for a grid convergence study (Celik et al., "Procedure
// for estimation and reporting of uncertainty due to discretization in CFD
// applications", J. Fluids Eng. 130, 2008; ASME V&V 20). Our own design on
// top of the job of mesh_job.h: member k (k = 0 .. N-1) is the job with every
// size asked for divided by r^k, so that its size field is the first
// member's scaled by 1/r^k:
//   - the wall's size (uniform {size}, or {per_circumference} N times r^k),
//     its clamps and refinement spheres' sizes, {core_size};
//   - the gradations (surface and volume) divided by r^k too, since a
//     field h(x) / s has slopes |grad h| / s;
//   - the boundary layer either refined with the family (the first layer
//     divided by r^k, in about r^k times as many layers of about the same
//     total thickness)
//     or kept as the first member's (one first-layer height, the y+ choice).
// Every member meshes the same prepared surface (one preparation: the same
// repairs, cuts, openings and names), so that the members differ by their
// resolution only; a deeper cut one member needs is kept for the next.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "core/pipeline/mesh_job.h"
#include "core/util/progress.h"
#include "core/util/result.h"

namespace vm {

/// "refine" or "fixed".
std::string_view family_layers_name(FamilyLayers layers);

/// Member k's options (0 <= k < options.family): `options` with its sizes
/// divided by options.family_ratio^k as above, family = 1. `per_circumference`:
/// the first member's edges per circumference as used (after the element
/// budget coarsened the default; 0: options' own). The member's sizes count
/// as given (size_given), so that a member over the element budget is
/// refused, never coarsened on its own.
MeshJobOptions family_member_options(const MeshJobOptions& options, int k,
                                     double per_circumference = 0);

/// One row of the family's table: what a member is, as a convergence study
/// reports it. Lengths in the model's unit (family_member_row) or the
/// written mesh's (run_mesh_family: MeshFamily::unit), volumes its cube.
struct FamilyMember {
  int index = 0;     ///< k
  double scale = 1;  ///< 1 / r^k: its sizes over the first member's
  std::string file;  ///< the file it was written to (set by the writer)
  size_t nodes = 0;  ///< vertices of the volume mesh
  size_t tetrahedra = 0, prisms = 0;
  size_t triangles = 0, quads = 0;  ///< boundary faces
  size_t wall_triangles = 0;
  size_t cells = 0;         ///< volume elements: tetrahedra + prisms
  double lumen_volume = 0;  ///< model units cubed
  /// Representative cell size (V / cells)^(1/3) of the lumen and the
  /// vessel wall together (Celik et al., eq. 1); model units.
  double h = 0;
  /// h of the previous member over this one's (0 for the first): the
  /// achieved refinement ratio, r when the refinement is exact.
  double ratio = 0;
  QualityStats quality;                                ///< gamma_t of every tetrahedron
  QualityStats core_quality;                           ///< gamma_t of the core's tetrahedra
  double wall_quality_min = 0, wall_quality_mean = 0;  ///< gamma_k of the wall
  /// The viscous layer: layers, the mean first-layer height and the mean
  /// total thickness (model units; 0 without a layer): the total is the
  /// layer's volume over the wall's area, the first its share of it by the
  /// layers' heights (growth).
  int layers = 0;
  double first_layer_height = 0, layer_thickness = 0;
  double per_circumference = 0;  ///< N of the per-circumference size (0: uniform)
  double size = 0;               ///< uniform size (0: per circumference)
  double seconds = 0;
};

/// A whole family: its members, in order, and what made it.
struct MeshFamily {
  int members = 0;
  double ratio = 1.4;
  FamilyLayers layers = FamilyLayers::kRefine;
  std::string unit;  ///< "mm", "cm", "m" (the written mesh's)
  std::vector<FamilyMember> rows;
};

/// Member k's row from its result; `previous_h`: h of member k - 1 (0 for
/// the first).
FamilyMember family_member_row(const MeshJobResult& result, const MeshJobOptions& options, int k,
                               double previous_h);

/// The family's table as CSV: a header line, then one line per member
/// (columns: member, file, scale, nodes, tetrahedra, prisms, cells,
/// lumen_volume, h, ratio, gamma_t_min, gamma_t_mean, core_gamma_t_min,
/// core_gamma_t_mean, wall_gamma_k_min, wall_gamma_k_mean, layers,
/// first_layer_height, layer_thickness, seconds), "." decimal, "\n" lines.
std::string family_csv(const MeshFamily& family);

/// The family as JSON: {members, ratio, layers, unit, rows: [{the CSV's
/// columns by name}]}.
std::string family_json(const MeshFamily& family);

/// Called with each member once meshed (k, its options, its result), to
/// write it before the next is meshed (the results are not kept). An error
/// stops the family.
using FamilyMemberFn =
    std::function<Status(int k, const MeshJobOptions& options, const MeshJobResult& result)>;

/// Meshes the family options.family members of the surface file
/// `file_bytes` (options.family >= 1; 1 is a single mesh). Progress runs
/// over the whole family. The table's file names are left empty. Errors:
/// the first member's error as run_mesh_job gives it; a later member's
/// prefixed with which member it is ("family member 3 of 3 (sizes / 1.96):
/// ...").
Result<MeshFamily> run_mesh_family(std::span<const uint8_t> file_bytes,
                                   const MeshJobOptions& options, const FamilyMemberFn& on_member,
                                   const ProgressFn& progress = {});

}  // namespace vm
