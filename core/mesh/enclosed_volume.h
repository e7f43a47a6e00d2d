// Volume enclosed by a closed oriented triangle surface, by the divergence
// theorem: a check of capped surfaces (Marchandise et al., section 2: the
// wall closed by planar caps bounds the lumen to be meshed).
#pragma once

#include "core/mesh/surface_mesh.h"

namespace vm {

/// Signed volume enclosed by `mesh`: the sum over triangles (a, b, c) of
/// det[a - o, b - o, c - o] / 6, o the center of the bounding box (any o
/// gives the same value for a closed surface; the center keeps the terms
/// small). Positive when the triangles face outward (counterclockwise seen
/// from outside), negative when they face inward; model units cubed.
/// Precondition for the meaning: closed and consistently oriented (for an
/// open surface the value depends on o). 0 for an empty mesh.
double enclosed_volume(const SurfaceMesh& mesh);

/// Total area of the triangles of `mesh` (model units squared).
double surface_area(const SurfaceMesh& mesh);

}  // namespace vm
