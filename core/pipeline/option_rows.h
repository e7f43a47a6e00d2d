// The option table's rows (option_table.h), for the files that hold them
// (option_rows_*.cpp, one a group of the help) and option_table.cpp, which
// joins them. Not for other includers: use option_table.h.
#pragma once

#include <cmath>
#include <span>
#include <string>
#include <string_view>

#include "core/pipeline/option_table.h"

namespace vm::option_rows {

/// The rows of the input and size options (option_rows_input.cpp).
std::span<const OptionSpec> input_and_size();
/// The rows of the volume and layer options (option_rows_volume.cpp).
std::span<const OptionSpec> volume_and_layers();
/// The rows of the output, advanced and phantom options
/// (option_rows_output.cpp).
std::span<const OptionSpec> output_advanced_phantom();

using T = OptionType;
using O = MeshJobOptions;
using P = PhantomOptions;
using V = OptionValue;

constexpr uint8_t kInfoMesh = kCommandInfo | kCommandMesh;

/// Choices that rows of several groups take.
inline constexpr std::string_view kUnits[] = {"mm", "cm", "m"};
inline constexpr std::string_view kOffAuto[] = {"off", "auto"};

/// The shortest of %.15g .. %.17g that reads back to x exactly.
std::string shortest_text(double x);

/// A number's text as the rows read it.
inline std::string num(double x) { return shortest_text(x); }
/// x's text when it is set (> 0), else "" (unset).
inline std::string positive(double x) { return x > 0 ? shortest_text(x) : ""; }
/// A flag's text.
inline std::string flag(bool on) { return on ? "true" : "false"; }

}  // namespace vm::option_rows
