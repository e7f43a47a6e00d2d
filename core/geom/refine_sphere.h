// Local refinement: spheres where the user asks for a smaller size (the
// `--refine X,Y,Z,R,H` option). Inside a sphere the size is at most H; out
// of it the bound grows with the distance to the sphere at the field's
// gradation g, so that the field stays g-Lipschitz:
//
//   h_s(x) = H + g max(0, |x - c| - R)
//
// The surface size field and the volume size field both take the minimum
// of their own value and h_s over the spheres.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "core/util/portable_math.h"

namespace vm {

struct RefineSphere {
  std::array<double, 3> center{};  ///< model units
  double radius = 0;               ///< > 0, model units
  double size = 0;                 ///< H > 0, model units
};

/// min over `spheres` of h_s(x) (x: 3 doubles), infinity without spheres.
inline double refine_size(const std::vector<RefineSphere>& spheres, const double* x,
                          double gradation) {
  double h = std::numeric_limits<double>::infinity();
  for (const RefineSphere& s : spheres) {
    const double d = pm::hypot(x[0] - s.center[0], x[1] - s.center[1], x[2] - s.center[2]);
    h = std::min(h, s.size + gradation * std::max(0.0, d - s.radius));
  }
  return h;
}

}  // namespace vm
