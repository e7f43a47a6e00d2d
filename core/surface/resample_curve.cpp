// Arc-length resampling by the integral of 1 / h (Marchandise et al. 2.1).
#include "core/surface/resample_curve.h"

#include <algorithm>
#include <cmath>

namespace vm {

std::vector<CurveSample> resample_curve(const std::vector<double>& points,
                                        const std::vector<double>& sizes, bool closed,
                                        size_t min_segments) {
  const size_t n = points.size() / 3;
  const size_t segs = closed ? n : (n > 0 ? n - 1 : 0);
  std::vector<double> steps(segs + 1, 0.0);
  for (size_t i = 0; i < segs; ++i) {
    const size_t j = (i + 1) % n;
    double d2 = 0;
    for (int k = 0; k < 3; ++k) {
      double d = points[3 * j + k] - points[3 * i + k];
      d2 += d * d;
    }
    // Exact integral of 1 / h for h linear along the segment.
    const double h0 = sizes[i], h1 = sizes[j], len = std::sqrt(d2);
    const double inv = std::abs(h1 - h0) > 1e-12 * h0 ? std::log(h1 / h0) / (h1 - h0) : 1 / h0;
    steps[i + 1] = steps[i] + len * inv;
  }
  const size_t count = std::max(min_segments, size_t(std::lround(steps[segs])));
  std::vector<CurveSample> out;
  out.reserve(count);
  for (size_t s = 0, i = 0; s < count; ++s) {
    const double target = steps[segs] * double(s) / double(count);
    while (i + 1 < segs && steps[i + 1] <= target) ++i;
    const double f = steps[i + 1] > steps[i] ? (target - steps[i]) / (steps[i + 1] - steps[i]) : 0;
    out.push_back({i, std::clamp(f, 0.0, 1.0)});
  }
  return out;
}

}  // namespace vm
