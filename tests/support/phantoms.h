// Phantom helpers shared by the tests of the surface stages.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>

#include "core/phantom/vessel_phantom.h"

namespace vm::testing {

/// A generated vessel surface (empty, with a test failure, on error).
inline SurfaceMesh phantom(PhantomKind kind, bool open_ends, double voxel, double noise = 0) {
  PhantomOptions o;
  o.kind = kind;
  o.open_ends = open_ends;
  o.voxel = voxel;
  o.noise = noise;
  auto r = make_vessel_phantom(o);
  EXPECT_TRUE(r.ok()) << r.message();
  return r.ok() ? r.value() : SurfaceMesh{};
}

/// Index of the truth opening whose center is nearest to `centroid`.
inline size_t nearest_truth_opening(const PhantomTruth& truth, const double* centroid) {
  size_t best = 0;
  double best_d = 1e300;
  for (size_t i = 0; i < truth.opening_centers.size(); ++i) {
    double d = 0;
    for (int k = 0; k < 3; ++k) d += std::pow(centroid[k] - truth.opening_centers[i][k], 2);
    if (d < best_d) best_d = d, best = i;
  }
  return best;
}

}  // namespace vm::testing
