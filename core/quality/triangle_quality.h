// Triangle quality gamma_k of the seed paper (Marchandise et al., section 3):
// gamma = 4 sin a sin b sin c / (sin a + sin b + sin c) = 2 r_in / r_circ,
// 1 for the equilateral triangle, 0 for a degenerate one: over a whole mesh,
// and the summary (min, mean, histogram) of any measure in [0, 1]. The
// formula of one triangle, triangle_gamma, is geom/triangle_gamma.h's.
#pragma once

#include <cstddef>
#include <vector>

#include "core/geom/triangle_gamma.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

/// Distribution summary of a quality measure in [0, 1].
struct QualityStats {
  double min = 0;
  double mean = 0;
  double max = 0;
  size_t count = 0;
  /// Equal-width bins over [0, 1]; bin i counts values in [i/n, (i+1)/n),
  /// with 1.0 in the last bin.
  std::vector<size_t> histogram;
};

/// gamma_k of every triangle of `mesh` (num_triangles() values).
std::vector<float> triangle_qualities(const SurfaceMesh& mesh);

/// Summary of `values` with `bins` histogram bins. Precondition: bins >= 1.
QualityStats quality_stats(const std::vector<float>& values, int bins = 20);

}  // namespace vm
