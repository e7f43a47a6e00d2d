// Reading the CLI's input file: a path, or '-' for standard input (a pipe
// or a redirected file); directories and devices are refused as such, and
// sizes beyond the readers' limits before the file is read.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/io/read_surface.h"
#include "core/util/result.h"

namespace vm::cli {

/// The bytes of `path` ('-': standard input). Errors name the path and say
/// what it is ("a directory", "a device", "a terminal") or why it cannot be
/// read; a regular file is checked with check_surface_size first, a stream
/// is read in chunks up to options.max_file_bytes.
Result<std::vector<uint8_t>> read_input(const std::string& path,
                                        const SurfaceReadOptions& options = {});

}  // namespace vm::cli
