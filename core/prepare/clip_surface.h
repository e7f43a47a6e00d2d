// Clipping a closed vessel surface open: at its vessel ends, or by planes the
// user gives, each cut becoming a planar opening.
#pragma once

#include <array>

namespace vm {

/// A cutting plane: a point on it and the unit normal pointing to the side
/// that is removed (out of the part kept).
struct ClipPlane {
  std::array<double, 3> point{};
  std::array<double, 3> normal{};
};

}  // namespace vm
