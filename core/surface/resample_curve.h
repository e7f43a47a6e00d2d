// Resampling of a polyline at a target size, shared by patch boundaries and
// seams so that neighbors discretize a shared curve once, identically
// (Marchandise et al., section 2.1).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vm {

/// A sample on a polyline: on segment `segment` (from vertex i to i + 1,
/// wrapping for closed curves) at fraction t in [0, 1).
struct CurveSample {
  size_t segment = 0;
  double t = 0;
};

/// Places samples along the polyline through `points` (3 doubles each; n
/// points, n segments if closed, n - 1 otherwise) at unit steps of the
/// integral of 1 / h, where `sizes` gives h at each point (> 0, linear in
/// between). The first sample is the first point; an open curve's last
/// point is not returned (it belongs to the next curve). The number of
/// segments is the integral rounded, at least `min_segments`.
std::vector<CurveSample> resample_curve(const std::vector<double>& points,
                                        const std::vector<double>& sizes, bool closed,
                                        size_t min_segments);

}  // namespace vm
