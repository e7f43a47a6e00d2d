// Per-solver presets and the application of a user's options under them
// (solver_preset.h).
#include "core/pipeline/solver_preset.h"

#include "core/pipeline/option_values.h"
#include "core/pipeline/validate_options.h"
#include "core/pipeline/write_outputs.h"
#include "core/util/json_writer.h"

namespace vm {
namespace {

// The presets. To change what a solver gets by default (the format when
// the output's name does not say, say), change its row here.
const SolverPreset kPresets[] = {
    {.solver = Solver::kGmsh,
     .name = "gmsh",
     .label = "Gmsh (plain defaults)",
     .keep_prisms = false,
     .format = OutputFormat::kMsh,
     .msh_version = MshVersion::k41,
     .output_units = LengthUnit::kGuess,
     .note = ""},
    {.solver = Solver::kOpenFoam,
     .name = "openfoam",
     .label = "OpenFOAM (polyMesh case)",
     .keep_prisms = true,
     // The native case (foam_writer.h): `wall` a wall patch, cell zones
     // named; MSH 2.2 when the output's name asks for .msh (gmshToFoam).
     .format = OutputFormat::kFoam,
     .msh_version = MshVersion::k22,
     .output_units = LengthUnit::kM,
     .note = "constant/polyMesh is ready: wall is a wall patch, the openings are patches, the "
             "volume groups are cell zones; add the 0/ fields and your system/ dictionaries (a "
             ".msh output is MSH 2.2 for gmshToFoam, which makes every patch a patch)"},
    {.solver = Solver::kFenics,
     .name = "fenics",
     .label = "FEniCS (dolfinx)",
     .keep_prisms = false,
     .format = OutputFormat::kMsh,
     .msh_version = MshVersion::k41,
     .output_units = LengthUnit::kGuess,
     .note = "read with gmsh.open and dolfinx.io.gmshio.model_to_mesh (dolfinx 0.5's "
             "read_from_msh fails): cell tags are the volume groups' tags, facet tags the surface "
             "groups'"},
    {.solver = Solver::kSvFsi,
     .name = "svfsi",
     .label = "svFSI (SimVascular mesh-complete)",
     .keep_prisms = false,
     .format = OutputFormat::kMeshComplete,
     .msh_version = MshVersion::k41,
     .output_units = LengthUnit::kGuess,
     .note = "mesh-complete.mesh.vtu is the volume, mesh-surfaces/<name>.vtp the faces svFSI's "
             "input file names; with a vessel wall, fluid/ and solid/ each such a folder, sharing "
             "the interface wall.vtp"},
};

bool given(std::span<const std::pair<const OptionSpec*, OptionValue>> values, std::string_view id) {
  for (const auto& [spec, value] : values)
    if (spec->id == id) return true;
  return false;
}

}  // namespace

std::span<const SolverPreset> solver_presets() { return kPresets; }

const SolverPreset* find_solver_preset(Solver solver) {
  for (const SolverPreset& p : kPresets)
    if (p.solver == solver) return &p;
  return nullptr;
}

const SolverPreset* find_solver_preset(std::string_view name) {
  for (const SolverPreset& p : kPresets)
    if (p.name == name) return &p;
  return nullptr;
}

Status apply_options(MeshJobOptions& options,
                     std::span<const std::pair<const OptionSpec*, OptionValue>> values) {
  const SolverPreset* preset = nullptr;
  for (const auto& [spec, value] : values)
    if (spec->id == "solver") preset = find_solver_preset(std::string_view(value.text));
  if (preset) {
    options.solver = preset->solver;
    PresetOutcome& out = options.preset;
    out = {};
    out.solver = std::string(preset->name);
    out.note = std::string(preset->note);
    // The preset's defaults; an option the user gave is applied after them
    // and wins.
    options.keep_prisms = preset->keep_prisms;
    options.msh_version = preset->msh_version;
    options.output_units = preset->output_units;
    auto record = [&](std::string_view id, std::string_view value) {
      out.settings.push_back({std::string(id), std::string(value), !given(values, id)});
    };
    record("prisms", preset->keep_prisms ? "true" : "false");
    record("msh_version", msh_version_word(preset->msh_version));
    if (preset->output_units != LengthUnit::kGuess)
      record("output_units", unit_symbol(preset->output_units));
  }
  for (const auto& [spec, value] : values)
    if (Status st = apply_option(options, *spec, value); !st.ok()) return st;
  if (preset) {  // the user's values where the user gave them
    for (PresetSetting& s : options.preset.settings) {
      if (s.from_preset) continue;
      if (s.id == "prisms") s.value = options.keep_prisms ? "true" : "false";
      if (s.id == "msh_version") s.value = msh_version_word(options.msh_version);
      if (s.id == "output_units") s.value = unit_symbol(options.output_units);
    }
  }
  const bool yplus = given(values, "first_layer_yplus");
  for (std::string_view id : {"inlet_velocity", "density", "viscosity"})
    if (!yplus && given(values, id))
      return Status::BadOption(std::string(id),
                               "sizes the first layer from a target y+: give {first_layer_yplus} "
                               "too, or leave it out");
  return validate_options(options, options.format);
}

OutputFormat resolve_output_format(MeshJobOptions& options, std::optional<OutputFormat> from_name) {
  const SolverPreset* preset = find_solver_preset(options.solver);
  const OutputFormat format = options.format ? *options.format
                              : from_name    ? *from_name
                              : preset       ? preset->format
                                             : OutputFormat::kMsh;
  if (preset) {
    auto& settings = options.preset.settings;
    std::erase_if(settings, [](const PresetSetting& s) { return s.id == "format"; });
    settings.push_back({"format", std::string(format_name(format)), !options.format && !from_name});
  }
  return format;
}

std::string preset_summary(const PresetOutcome& preset) {
  if (preset.solver.empty()) return "";
  std::string ours, yours;
  for (const PresetSetting& s : preset.settings) {
    std::string& list = s.from_preset ? ours : yours;
    list += (list.empty() ? "" : ", ") + s.id + " " + (s.value.empty() ? "input's" : s.value);
  }
  std::string text = preset.solver + ": " + (ours.empty() ? "nothing" : ours) + " (the preset)";
  if (!yours.empty()) text += "; " + yours + " (yours)";
  return text;
}

std::string solver_presets_json() {
  JsonWriter j;
  j.begin_array();
  for (const SolverPreset& p : kPresets) {
    j.begin_object();
    j.key("name").value(p.name);
    j.key("label").value(p.label);
    j.key("prisms").value(p.keep_prisms);
    j.key("format").value(format_name(p.format));
    j.key("mshVersion").value(msh_version_word(p.msh_version));
    j.key("outputUnits").value(unit_symbol(p.output_units));
    j.key("note").value(p.note);
    j.end_object();
  }
  j.end_array();
  return j.str();
}

}  // namespace vm
