// A local vessel radius for the layer thickness (Marchandise et al.,
// sections 2.2 and 4.3: thicknesses as fractions of the local radius R(x),
// e.g. a vessel wall of 0.1 R): half the chord of the lumen along the
// inward normal at each wall vertex, found by casting a ray through a box
// hierarchy of the wall.
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm {

/// R per wall vertex (model units): half the distance from the vertex along
/// its inward angle-weighted normal to the first wall triangle the ray
/// meets (triangles at the vertex excluded), then two passes of a 1-ring
/// median. Exact R for a circular tube; across a branch the chord of the
/// branch; vertices whose ray leaves through an opening take the median of
/// their neighbors, grown in from the vertices that have a value (half the
/// bounding-box diagonal only if no ray meets the wall at all).
/// O(n log n). Unlike surface/vessel_radius.h (maximal inscribed balls,
/// whose shrinking can stop at the initial ball on curved branches), every
/// value is a length actually measured across the lumen.
/// Preconditions: manifold, outward oriented, every vertex in a triangle.
std::vector<double> chord_radius(const SurfaceMesh& wall);

/// The raw measure at the given wall vertices only (one value per entry of
/// `vertices`): half the distance along the inward angle-weighted normal to
/// the first wall triangle the ray meets, -1 where it meets none (it leaves
/// through an opening). No smoothing. Same preconditions.
std::vector<double> half_chords(const SurfaceMesh& wall, const std::vector<int32_t>& vertices);

}  // namespace vm
