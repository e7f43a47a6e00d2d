// Local vessel radius R(x) at the surface vertices, for the radius-adaptive
// size field h = 2 pi R / N (Marchandise et al., eq. 11).
#pragma once

#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm {

/// Radius of the maximal inscribed ball touching each vertex, by the
/// shrinking-ball method (Ma, Bai and Kim, "3D medial axis point
/// approximation using nearest neighbors and the normal field", Visual
/// Computer 28, 2012) with their separation-angle denoising, then two passes
/// of a median over each vertex's 1-ring to remove remaining outliers.
/// Returns num_vertices radii in model units. Preconditions: manifold,
/// outward oriented (inward normals point into the lumen), at least one
/// triangle. Vertices whose ball never closes (e.g. facing an opening) get
/// the median of their neighbors, or at most half the bounding-box diagonal.
/// An oversampled surface (more than `sample_above` vertices) has its balls
/// shrunk at about `samples` vertices spread evenly (one per cell of a grid
/// of edge sqrt(area / samples)); every other
/// vertex takes the value of the sample vertex nearest along the edges.
/// The sample is far denser than any vessel radius for the surfaces this
/// applies to (a quarter million triangles and more).
struct VesselRadiusSampling {
  size_t sample_above = 120'000;
  size_t samples = 50'000;
};

std::vector<double> vessel_radius(const SurfaceMesh& mesh,
                                  const VesselRadiusSampling& sampling = {});

}  // namespace vm
