// gamma_k = 2 r_in / r_circ (Marchandise et al., section 3), computed from
// the edge lengths: r_in = 2A / (a + b + c), r_circ = a b c / (4A), so
// gamma = 16 A^2 / (a b c (a + b + c)).
#include "core/quality/triangle_quality.h"

#include <algorithm>
#include <cmath>

#include "core/util/parallel.h"

namespace vm {

double triangle_gamma(const double* a, const double* b, const double* c) {
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = b[k] - a[k];
    v[k] = c[k] - a[k];
    w[k] = c[k] - b[k];
  }
  double cx = u[1] * v[2] - u[2] * v[1];
  double cy = u[2] * v[0] - u[0] * v[2];
  double cz = u[0] * v[1] - u[1] * v[0];
  double area2 = cx * cx + cy * cy + cz * cz;  // (2A)^2
  double la = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  double lb = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  double lc = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  double den = la * lb * lc * (la + lb + lc);
  if (!(den > 0)) return 0.0;
  // 16 A^2 = 4 (2A)^2.
  return std::clamp(4.0 * area2 / den, 0.0, 1.0);
}

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
