// Per-vertex mean edge length: a size for vertices without a target size
// (an input used as it is, cap interiors) and a local scale for searches.
#include "core/mesh/edge_lengths.h"

#include <cmath>

namespace vm {

std::vector<double> mean_edge_lengths(const SurfaceMesh& m) {
  std::vector<double> sum(m.num_vertices(), 0.0), count(m.num_vertices(), 0.0);
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = m.triangles[3 * t + size_t(k)];
      const int32_t b = m.triangles[3 * t + size_t((k + 1) % 3)];
      const double* pa = &m.points[3 * size_t(a)];
      const double* pb = &m.points[3 * size_t(b)];
      const double l =
          std::sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) +
                    (pa[2] - pb[2]) * (pa[2] - pb[2]));
      for (int32_t v : {a, b}) sum[size_t(v)] += l, count[size_t(v)] += 1;
    }
  for (size_t v = 0; v < sum.size(); ++v) sum[v] = count[v] > 0 ? sum[v] / count[v] : 0;
  return sum;
}

}  // namespace vm
