// Gap limit of the boundary layer: how much room there is in front of each
// wall vertex before the front would meet another part of the wall (a
// facing wall across a narrowing, the neighbor branch at a bifurcation
// crotch, the other side of a tight bend). Marchandise et al., section 2.2
// ("prevent element overlap in regions of tight corners"); the empty-ball
// measure is the shrinking-ball medial radius of Ma, Bai and Kim, "3D medial
// axis point approximation using nearest neighbors and the normal field",
// Visual Computer 28, 2012, with their separation-angle denoising.
#pragma once

#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm {

/// Radius of the largest ball tangent at each wall vertex v, its center
/// along `normal` (3 doubles per vertex, unit, on the layer side), that
/// contains no wall vertex q "across" from v: q counts when the angle
/// between v and q seen from the center of the ball through both is at
/// least `separation_degrees` (smaller angles are the wall's own nearby
/// shape, bumps and gentle curvature, which the local validity check
/// handles). Capped at needed[v]: the search covers only the ball of that
/// radius, so a vertex with room costs one radius query. needed[v] <= 0:
/// radius[v] = needed[v]. k-d tree (nanoflann); O(n log n) for needed
/// radii of a few edge lengths. Twice the radius is the local gap between
/// facing walls, or between the two sides of a fold of the front.
/// exact = false: when the 64 nearest vertices to a ball's center are all
/// inside it and next to v, the ball is kept as it is instead of settling
/// it by a radius query (Ma et al.'s own stopping rule; cheaper for balls
/// of many edge lengths, may overestimate on noisy walls).
std::vector<double> empty_ball_radius(const SurfaceMesh& wall, const std::vector<double>& normal,
                                      const std::vector<double>& needed,
                                      double separation_degrees = 60, bool exact = true);

}  // namespace vm
