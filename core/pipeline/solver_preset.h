// Per-solver presets (`--for openfoam|fenics|svfsi|gmsh`, JS `solver`):
// defaults of element types, output format, MSH version and output unit
// that suit one solver, applied under the user's own options (an option
// given explicitly, or an output name's extension, always wins). Why each:
// - openfoam: finite volumes want the layers' prisms (split prisms gave
//   checkMesh faces above 70 degrees of non-orthogonality, and simpleFoam
//   did not converge on them; validation/solver_check.py); gmshToFoam reads MSH 2.2; OpenFOAM
//   works in metres, so the mesh is converted from the input's unit.
// - fenics: dolfinx reads one cell type: the prisms split into tetrahedra;
//   MSH 4.1 (its Gmsh reader).
// - svfsi: tetrahedra, SimVascular's mesh-complete folder.
// - gmsh: the plain defaults (MSH 4.1, tetrahedra, the input's unit).
#pragma once

#include <optional>
#include <span>
#include <string_view>
#include <utility>

#include "core/io/msh_writer.h"
#include "core/io/output_file.h"
#include "core/pipeline/mesh_job.h"
#include "core/pipeline/option_table.h"
#include "core/prepare/units.h"
#include "core/util/result.h"

namespace vm {

/// What a preset sets. This table (solver_preset.cpp) is the one place
/// where a solver's defaults are chosen, its default output format
/// included.
struct SolverPreset {
  Solver solver = Solver::kNone;
  std::string_view name;   ///< the option's value: "openfoam"
  std::string_view label;  ///< for people: "OpenFOAM (gmshToFoam)"
  bool keep_prisms = false;
  OutputFormat format = OutputFormat::kMsh;  ///< when neither {format} nor the output name says
  MshVersion msh_version = MshVersion::k41;
  LengthUnit output_units = LengthUnit::kGuess;  ///< kGuess: the input's unit
  /// What the solver needs beyond the file, for the report ("" = nothing).
  std::string_view note;
};

/// Every preset, in the option's order (gmsh, openfoam, fenics, svfsi).
std::span<const SolverPreset> solver_presets();
/// The preset of `solver`, or nullptr (kNone).
const SolverPreset* find_solver_preset(Solver solver);
/// The preset named `name`, or nullptr.
const SolverPreset* find_solver_preset(std::string_view name);

/// Applies option values given by a user (CLI or JS, in the order given) to
/// `options`: the solver preset's defaults first (when a `solver` value is
/// among them), recorded in options.preset with each setting marked as the
/// user's when the user gave that option; then every value with
/// apply_option. Refuses the flow options given without a target y+
/// ({inlet_velocity}, {density}, {viscosity} without
/// {first_layer_yplus}), then checks the options as a whole
/// (validate_options, with {format} when given). Errors are
/// apply_option's, or kBadOption.
Status apply_options(MeshJobOptions& options,
                     std::span<const std::pair<const OptionSpec*, OptionValue>> values);

/// The format to write: {format} when given, else `from_name` (what the
/// output's name says: its extension, or a folder), else the preset's
/// default, else MSH. With a preset, records the format in options.preset
/// (as the user's when it came from {format} or the name).
OutputFormat resolve_output_format(MeshJobOptions& options, std::optional<OutputFormat> from_name);

/// One line for people: "openfoam: prisms true, msh_version 2.2,
/// output_units m (the preset); format vtu (yours)", "" without a preset.
std::string preset_summary(const PresetOutcome& preset);

/// The presets as JSON for the JS side: [{name, label, prisms, format,
/// mshVersion, outputUnits ("" = the input's), note}].
std::string solver_presets_json();

}  // namespace vm
