// Arc-length resampling by the integral of 1 / h (Marchandise et al. 2.1).
#include "core/surface/resample_curve.h"

#include <algorithm>
#include <cmath>

#include "core/util/portable_math.h"

namespace vm {

std::vector<CurveSample> resample_curve(const std::vector<double>& points,
                                        const std::vector<double>& sizes, bool closed,
                                        size_t min_segments) {
  const size_t n = points.size() / 3;
  const size_t segs = closed ? n : (n > 0 ? n - 1 : 0);
  std::vector<double> steps(segs + 1, 0.0), lengths(segs, 0.0);
  auto graded = [&](size_t i) {
    const double h0 = sizes[i], h1 = sizes[(i + 1) % n];
    return std::abs(h1 - h0) > 1e-9 * h0;
  };
  for (size_t i = 0; i < segs; ++i) {
    const size_t j = (i + 1) % n;
    double d2 = 0;
    for (int k = 0; k < 3; ++k) {
      double d = points[3 * j + k] - points[3 * i + k];
      d2 += d * d;
    }
    // Exact integral of 1 / h for h linear along the segment.
    const double h0 = sizes[i], h1 = sizes[j];
    lengths[i] = std::sqrt(d2);
    const double inv = graded(i) ? pm::log(h1 / h0) / (h1 - h0) : 1 / h0;
    steps[i + 1] = steps[i] + lengths[i] * inv;
  }
  const size_t count = std::max(min_segments, size_t(std::lround(steps[segs])));
  std::vector<CurveSample> out;
  out.reserve(count);
  for (size_t s = 0, i = 0; s < count; ++s) {
    const double target = steps[segs] * double(s) / double(count);
    while (i + 1 < segs && steps[i + 1] <= target) ++i;
    // Invert the integral within the segment: with h(f) = h0 + (h1 - h0) f,
    // the integral up to f is L / (h1 - h0) ln(h(f) / h0).
    const double part = target - steps[i], h0 = sizes[i], h1 = sizes[(i + 1) % n];
    double f = 0;
    if (steps[i + 1] > steps[i] && lengths[i] > 0)
      f = graded(i) ? (h0 * pm::exp(part * (h1 - h0) / lengths[i]) - h0) / (h1 - h0)
                    : part * h0 / lengths[i];
    out.push_back({i, std::clamp(f, 0.0, 1.0)});
  }
  return out;
}

}  // namespace vm
