// A tube with a dent pushed through the opposite wall: the self-crossing a
// segmentation makes when one wall is pushed through the lumen.
#pragma once

#include <cmath>
#include <numbers>

#include "core/mesh/surface_mesh.h"
#include "tests/support/test_meshes.h"

namespace vm::testing {

/// Dents the wall of a tube of radius 1 along z: a Gaussian bump (width
/// 0.35) at height `z` moved by `push` across the tube, from angle 0
/// towards -x for a positive push, from angle pi towards +x for a negative
/// one. |push| 2.6 takes the wall's point 0.6 past the opposite wall.
inline void push_dent(SurfaceMesh& s, double z, double push) {
  const double from = push > 0 ? 0 : std::numbers::pi;
  for (size_t v = 0; v < s.num_vertices(); ++v) {
    double* p = &s.points[3 * v];
    const double a = std::atan2(p[1], p[0]) - from;
    const double d2 = 2 * (1 - std::cos(a)) + (p[2] - z) * (p[2] - z);
    p[0] -= push * std::exp(-d2 / (2 * 0.35 * 0.35));
  }
}

/// open_tube(48, 40, 1, 8) (z from 0 to 8) with a dent at (1, 0, 4) pushed
/// through the opposite wall (x = -1).
inline SurfaceMesh pushed_tube() {
  SurfaceMesh s = open_tube(48, 40, 1.0, 8.0);
  push_dent(s, 4, 2.6);
  return s;
}

}  // namespace vm::testing
