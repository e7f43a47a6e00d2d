// Command-line arguments through the option table (core/pipeline/
// option_table.h): parsing, the help text and the option list of docs/options.md.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/pipeline/option_table.h"
#include "core/pipeline/solver_preset.h"

namespace vm::cli {

/// A command line after parsing: positional arguments and option values in
/// the order given.
struct Args {
  std::vector<std::string> positional;
  std::vector<std::pair<const OptionSpec*, OptionValue>> values;
  std::string error;  ///< a usage error (unknown option, bad value...), phrased for the CLI

  /// The last value of option `id`, or nullptr.
  const OptionValue* get(std::string_view id) const;
};

/// Parses argv[first..] for `command`: `--name value`, `--name=value`,
/// flags, `-o FILE` for --output; values are checked against the table.
/// Non-repeatable options given twice are an error.
Args parse_args(int argc, char** argv, int first, OptionCommand command);

/// Applies every value to `options` (info and mesh commands); a usage error
/// message, or empty.
std::string apply_all(const Args& args, MeshJobOptions& options);
std::string apply_all(const Args& args, PhantomOptions& options);

/// The options section of --help for all commands, from the table.
std::string options_help();

/// The option list of docs/options.md (Markdown tables), from the table.
std::string options_markdown();

}  // namespace vm::cli
