// One file of a multi-file output (a `mesh-complete` folder, a ZIP archive's
// entries): its path relative to the output's root and its contents.
#pragma once

#include <string>

namespace vm {

/// path: relative, '/'-separated (e.g. "mesh-surfaces/wall.vtp"); bytes: the
/// file's contents (binary-safe).
struct OutputFile {
  std::string path;
  std::string bytes;
};

}  // namespace vm
