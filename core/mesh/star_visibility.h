// Visibility of a vertex's star: the direction that sees every incident
// triangle best, pushed towards the worst-seen one (as for the extrusion
// directions of advancing layers: Aubry and Lohner, IJNMF 2009). Shared by
// the boundary-layer directions and the remeshing's needle guard.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm {

/// From the unit direction d (3 doubles), moves it `max_steps` times at
/// most, while it sees some triangle of star[0 .. n) at a cosine below
/// `target`: d += (target - worst + 0.05) * (worst triangle's normal), then
/// constrain(d) (e.g. a projection into a plane), then normalized. Sets d
/// to the best direction met and returns its worst cosine (2 for an empty
/// star). unit_normals: 3 per triangle, unit length.
template <class Constrain>
double see_star(const int32_t* star, int32_t n, const double* unit_normals, double* d,
                double target, int max_steps, Constrain&& constrain) {
  auto worst = [&](const double* x, int32_t* which) {
    double w = 2;
    for (int32_t i = 0; i < n; ++i) {
      const double* tn = &unit_normals[3 * size_t(star[i])];
      const double c = x[0] * tn[0] + x[1] * tn[1] + x[2] * tn[2];
      if (c < w) w = c, *which = star[i];
    }
    return w;
  };
  double x[3] = {d[0], d[1], d[2]};
  int32_t t = -1;
  double w = worst(x, &t), best_w = w;
  for (int step = 0; step < max_steps && best_w < target && t >= 0; ++step) {
    const double* tn = &unit_normals[3 * size_t(t)];
    for (int k = 0; k < 3; ++k) x[k] += (target - w + 0.05) * tn[k];
    constrain(x);
    const double len = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    if (!(len > 0)) break;
    for (double& c : x) c /= len;
    w = worst(x, &t);
    if (w > best_w) best_w = w, d[0] = x[0], d[1] = x[1], d[2] = x[2];
  }
  return best_w;
}

/// Per vertex of `mesh`, how well one direction sees its star: see_star
/// from the area-weighted normal (target 0.3, 20 steps). 1 on a plane,
/// <= 0 for a needle or a fold no direction sees whole; 1 for a vertex
/// with no triangle.
std::vector<double> star_visibility(const SurfaceMesh& mesh);

}  // namespace vm
