// Frontal-Delaunay meshing of a planar domain: the default 2D mesher of the
// parameter plane (Marchandise et al., section 3 and Table 1, "Frontal").
#pragma once

#include <vector>

#include "core/mesh2d/delaunay_refinement.h"

namespace vm {

/// Meshes the domain bounded by `segments` (as constrained_delaunay) by
/// Rebay's frontal-Delaunay method (J. Comput. Phys. 106, 1993): a triangle
/// is accepted once its circumradius is at most
/// `options.frontal_radius_tolerance` times that of the equilateral triangle of side h; the largest
/// non-accepted triangle next to the front (the boundary or an accepted
/// triangle) gets a new point on the perpendicular bisector of its front
/// edge, placed so that the new triangle on that edge is as close to
/// equilateral of side h as the triangle's circumcircle allows. Points are
/// inserted by Delaunay insertion, so the mesh stays constrained Delaunay.
/// The boundary is kept as given (no point on a segment or inside a
/// segment's diametral circle). Errors: those of constrained_delaunay, a
/// non-positive size, the safety limit.
Result<Mesh2D> frontal_delaunay(const std::vector<double>& points,
                                const std::vector<int32_t>& segments, const SizeField2D& size,
                                const RefinementOptions& options = {});

}  // namespace vm
