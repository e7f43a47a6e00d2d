// gamma_k of every triangle of a mesh (the formula: geom/triangle_gamma.cpp)
// and the summary of a quality measure.
#include "core/quality/triangle_quality.h"

#include <algorithm>

#include "core/util/parallel.h"

namespace vm {

std::vector<float> triangle_qualities(const SurfaceMesh& mesh) {
  std::vector<float> q(mesh.num_triangles());
  parallel_for(q.size(), 1 << 15, [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t)
      q[t] = float(triangle_gamma(&mesh.points[3 * mesh.triangles[3 * t]],
                                  &mesh.points[3 * mesh.triangles[3 * t + 1]],
                                  &mesh.points[3 * mesh.triangles[3 * t + 2]]));
  });
  return q;
}

QualityStats quality_stats(const std::vector<float>& values, int bins) {
  QualityStats s;
  s.histogram.assign(size_t(std::max(bins, 1)), 0);
  s.count = values.size();
  if (values.empty()) return s;
  s.min = 1.0;
  s.max = 0.0;
  double sum = 0;
  for (float v : values) {
    s.min = std::min(s.min, double(v));
    s.max = std::max(s.max, double(v));
    sum += v;
    int b = int(double(v) * double(s.histogram.size()));
    b = std::clamp(b, 0, int(s.histogram.size()) - 1);
    ++s.histogram[b];
  }
  s.mean = sum / double(values.size());
  return s;
}

}  // namespace vm
