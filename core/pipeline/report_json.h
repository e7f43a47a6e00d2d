// JSON views of pipeline results, shared by the CLI (--json) and the
// WebAssembly API so that both speak the same keys.
#pragma once

#include <string>

#include "core/pipeline/mesh_job.h"
#include "core/pipeline/option_table.h"
#include "core/pipeline/prepare_surface.h"

namespace vm {

/// Keys: vertices, triangles, input_triangles, format (what the file was:
/// "binary STL", ...), label_array, units {unit, guessed, certain, reason},
/// bounding_box {min, max, diagonal}, components, openings [{perimeter,
/// radius, centroid, normal, vertices, source ("file" | "cap" | "clip"),
/// label, name (the group name it gets by default)}], caps_removed, clips
/// [{point, normal (the plane), centroid, radius, perimeter, area_removed}],
/// specks_removed (separate pieces under 1% of the largest), clip_proposals
/// [{point, normal (the plane clip auto would cut by), radius
/// (of that section), tip, depth (radii in from the tip)}] (a closed surface
/// not clipped),
/// smoothing {mode (auto | off | passes), staircase, direction_fraction,
/// lattice_fraction, terraces, voxel (null unless a staircase), spacing [3],
/// applied, passes, clamp_voxel (displacements are limited to half of it),
/// flat_regions (planar caps kept flat), max_displacement,
/// max_displacement_voxels (in units of clamp_voxel's sides), volume_change
/// (relative)}, closed, genus
/// (null if undefined), euler_characteristic, boundary_edges,
/// nonmanifold_edges, nonmanifold_vertices, repairs {...}, quality {min,
/// mean, max, histogram}, warnings [..]. Options in warnings are named in
/// the words of `face`.
std::string analysis_json(const PreparedSurface& surface, OptionFace face = kFaceCli);

/// Keys: input (analysis_json), preset (with a solver preset: solver,
/// settings [{option, value, from: "preset" | "user"}], note),
/// first_layer_yplus (when the first layer was sized from a y+: yplus,
/// inlet_velocity, density, viscosity, inlet, inlet_diameter (model unit),
/// reynolds, skin_friction, wall_shear_stress, friction_velocity, height_m,
/// height (model unit), correlation), output {unit, vertices, triangles,
/// quality, ..., groups [{dim, tag, name, elements}]}, warnings, seconds.
std::string mesh_report_json(const MeshJobResult& result, OptionFace face = kFaceCli);

}  // namespace vm
