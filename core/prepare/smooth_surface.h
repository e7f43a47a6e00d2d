// Smoothing of raw segmentation surfaces before remeshing: voxel staircases
// (marching cubes on a binary mask) are detected and smoothed without
// shrinking, and any surface may be smoothed on request.
#pragma once

#include <optional>
#include <string_view>

namespace vm {

/// How a surface is smoothed in preparation.
struct Smoothing {
  enum class Mode { kAuto, kOff, kPasses } mode = Mode::kAuto;
  int passes = 0;  ///< kPasses: the number of passes (1..1000)
};

/// "auto", "off" or a pass count 1..1000; nullopt for anything else.
std::optional<Smoothing> parse_smoothing(std::string_view text);

}  // namespace vm
