// Fixed-boundary maps of a disk-like patch onto the unit disk, for comparison
// with the least-squares conformal map (Marchandise et al., section 3 and
// Fig. 6): the boundary goes to the unit circle by chord length and each
// interior vertex is a weighted average of its neighbors.
#pragma once

#include "core/mesh/surface_mesh.h"
#include "core/param/lscm.h"
#include "core/util/result.h"

namespace vm {

enum class DiskWeights {
  /// Cotangent weights: the discrete harmonic map (may fold where weights
  /// are negative, i.e. on obtuse triangles).
  kHarmonic,
  /// Floater's mean-value weights: positive, so the map is one-to-one
  /// (Tutte-Floater) since the unit circle is convex.
  kMeanValue,
};

/// Maps `patch` onto the unit disk. Preconditions: connected, consistently
/// oriented, no repeated vertex in a triangle. Errors: not exactly one
/// boundary loop, a failed solve. The result's `pinned` are -1 (the whole
/// boundary is fixed) and its conformal_energy is E_LSCM of the map.
Result<Parametrization> map_to_disk(const SurfaceMesh& patch, DiskWeights weights);

}  // namespace vm
