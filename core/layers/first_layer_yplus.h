// The first boundary-layer height from a target y+, the way CFD users size
// layers: a skin-friction correlation gives the wall shear stress of the
// flow entering the inlet, hence the friction velocity u_tau, and the height
// at which y+ = y u_tau / nu is the target.
//
// Correlation: the turbulent flat-plate power law Cf = 0.026 Re^(-1/7) (a
// 1/7-power-law fit, the form common y+ estimators use), with the Reynolds
// number of the inlet, Re = rho U D / mu (D the inlet's equivalent
// diameter, in place of a plate length). For blood in large arteries (Re of
// a few hundred to a few thousand) the flow is laminar or transitional; the
// turbulent estimate gives a larger tau_w, so a smaller (conservative)
// first height.
//
//   tau_w = Cf rho U^2 / 2,  u_tau = sqrt(tau_w / rho),  y = y+ (mu / rho) / u_tau
#pragma once

namespace vm {

/// A target y+ and the flow that sets it, SI units.
struct YPlusTarget {
  double yplus = 0;           ///< the target y+ of the first layer (> 0)
  double velocity = 0;        ///< mean inlet velocity U, m/s (> 0)
  double density = 1060;      ///< rho, kg/m^3 (blood)
  double viscosity = 0.0035;  ///< dynamic viscosity mu, Pa s (blood)
};

/// The quantities of the estimate, SI units.
struct YPlusHeight {
  double reynolds = 0;           ///< rho U D / mu
  double skin_friction = 0;      ///< Cf = 0.026 Re^(-1/7)
  double wall_shear_stress = 0;  ///< tau_w = Cf rho U^2 / 2, Pa
  double friction_velocity = 0;  ///< u_tau = sqrt(tau_w / rho), m/s
  double height = 0;             ///< y = y+ mu / (rho u_tau), m
};

/// The first-layer height for `target` at an inlet of diameter
/// `diameter_m` (metres). Preconditions: every input > 0.
YPlusHeight first_layer_height_for_yplus(const YPlusTarget& target, double diameter_m);

}  // namespace vm
