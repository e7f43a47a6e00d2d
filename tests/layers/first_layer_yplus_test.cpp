#include "core/layers/first_layer_yplus.h"

#include <gtest/gtest.h>

namespace vm {
namespace {

// Expects the values of a hand computation: the Reynolds number within
// reynolds_tol, the others to their last digit given.
void expect_hand_computed(const YPlusHeight& h, double reynolds, double reynolds_tol,
                          double skin_friction, double wall_shear_stress, double friction_velocity,
                          double height) {
  EXPECT_NEAR(h.reynolds, reynolds, reynolds_tol);
  EXPECT_NEAR(h.skin_friction, skin_friction, 1e-8);
  EXPECT_NEAR(h.wall_shear_stress, wall_shear_stress, 1e-5);
  EXPECT_NEAR(h.friction_velocity, friction_velocity, 1e-7);
  EXPECT_NEAR(h.height, height, 1e-9);
}

// Hand computation, water in a 10 cm pipe at 1 m/s, y+ 30:
//   Re = 1000 * 1 * 0.1 / 0.001 = 1e5;  Re^(1/7) = 10^(5/7) = 5.17947
//   Cf = 0.026 / 5.17947 = 5.01981e-3
//   tau_w = 0.5 * 5.01981e-3 * 1000 * 1^2 = 2.50991 Pa
//   u_tau = sqrt(2.50991 / 1000) = 0.0500990 m/s
//   y = 30 * (0.001 / 1000) / 0.0500990 = 5.98815e-4 m
TEST(FirstLayerYPlus, MatchesAHandComputation) {
  const YPlusHeight h = first_layer_height_for_yplus({30, 1.0, 1000, 0.001}, 0.1);
  expect_hand_computed(h, 1e5, 1e-6, 5.01981e-3, 2.50991, 0.0500990, 5.98815e-4);
}

// Blood (the defaults) at 0.5 m/s in a 2 cm artery, y+ 1:
//   Re = 1060 * 0.5 * 0.02 / 0.0035 = 3028.57;  Re^(1/7) = 3.14282
//   Cf = 0.026 / 3.14282 = 8.27282e-3;  tau_w = 0.5 Cf 1060 0.25 = 1.09615 Pa
//   u_tau = sqrt(1.09615 / 1060) = 0.0321575 m/s
//   y = 1 * (0.0035 / 1060) / 0.0321575 = 1.02679e-4 m (0.103 mm)
TEST(FirstLayerYPlus, BloodDefaults) {
  YPlusTarget t;
  t.yplus = 1;
  t.velocity = 0.5;
  const YPlusHeight h = first_layer_height_for_yplus(t, 0.02);
  expect_hand_computed(h, 3028.571, 1e-3, 8.27282e-3, 1.09615, 0.0321575, 1.02679e-4);
}

TEST(FirstLayerYPlus, HeightIsProportionalToYPlus) {
  const YPlusHeight a = first_layer_height_for_yplus({1, 0.3, 1060, 0.0035}, 0.008);
  const YPlusHeight b = first_layer_height_for_yplus({5, 0.3, 1060, 0.0035}, 0.008);
  EXPECT_NEAR(b.height, 5 * a.height, 1e-15);
  // A faster flow has a thinner viscous sublayer.
  EXPECT_LT(first_layer_height_for_yplus({1, 0.6, 1060, 0.0035}, 0.008).height, a.height);
}

}  // namespace
}  // namespace vm
