// The text forms of option values: each word a user may give an option
// (CLI text, JS string) and the value it stands for in the job's options,
// both ways. The option table's rows (option_rows_*.cpp) set and read the
// job's options through these; nothing below the option layer parses a
// user's words.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "core/io/msh_writer.h"
#include "core/io/output_file.h"
#include "core/phantom/vessel_phantom.h"
#include "core/pipeline/mesh_job.h"
#include "core/prepare/smooth_surface.h"
#include "core/prepare/units.h"
#include "core/surface/remesh_patch.h"
#include "core/surface/remesh_surface.h"
#include "core/util/result.h"

namespace vm {

/// kGuess for anything but "mm", "cm", "m" (the symbols of unit_symbol).
LengthUnit parse_unit(std::string_view symbol);

/// "auto", "off" or a pass count 1..1000; nullopt for anything else.
std::optional<Smoothing> parse_smoothing(std::string_view text);
/// The text parse_smoothing reads back: "auto", "off" or the pass count.
std::string smoothing_text(const Smoothing& smoothing);

/// The format of a name as format_name (write_outputs.h) gives it.
Result<OutputFormat> parse_format(std::string_view name);

/// The words of the choice options and their values, both ways; a word
/// that is not one of the option's choices gives its first value (the
/// table's check has refused it before).
ParamMethod param_method_of(std::string_view word);
std::string_view param_method_word(ParamMethod method);
Mesher2D mesher2d_of(std::string_view word);
std::string_view mesher2d_word(Mesher2D mesher);
MshVersion msh_version_of(std::string_view word);
std::string_view msh_version_word(MshVersion version);
/// kNone for "" (no preset).
Solver solver_of(std::string_view word);
std::string_view solver_word(Solver solver);
FamilyLayers family_layers_of(std::string_view word);
std::string_view family_layers_word(FamilyLayers layers);
PhantomKind phantom_kind_of(std::string_view word);
std::string_view phantom_kind_word(PhantomKind kind);
PhantomCapShape cap_shape_of(std::string_view word);
std::string_view cap_shape_word(PhantomCapShape shape);

}  // namespace vm
