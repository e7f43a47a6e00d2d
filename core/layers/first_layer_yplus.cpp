// First-layer height from a target y+ (first_layer_yplus.h).
#include "core/layers/first_layer_yplus.h"

#include <cmath>

#include "core/util/portable_math.h"

namespace vm {

YPlusHeight first_layer_height_for_yplus(const YPlusTarget& t, double diameter_m) {
  YPlusHeight h;
  h.reynolds = t.density * t.velocity * diameter_m / t.viscosity;
  h.skin_friction = 0.026 * pm::pow(h.reynolds, -1.0 / 7.0);
  h.wall_shear_stress = 0.5 * h.skin_friction * t.density * t.velocity * t.velocity;
  h.friction_velocity = std::sqrt(h.wall_shear_stress / t.density);
  h.height = t.yplus * (t.viscosity / t.density) / h.friction_velocity;
  return h;
}

}  // namespace vm
