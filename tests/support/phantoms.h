// Phantom helpers shared by the tests of the surface stages.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include "core/mesh/topology.h"
#include "core/phantom/vessel_phantom.h"

namespace vm::testing {

/// A generated vessel surface (empty, with a test failure, on error); its
/// truth in `truth` when given.
inline SurfaceMesh phantom(const PhantomOptions& o, PhantomTruth* truth = nullptr) {
  auto r = make_vessel_phantom(o, truth);
  EXPECT_TRUE(r.ok()) << r.message();
  return r.ok() ? r.value() : SurfaceMesh{};
}

/// The same for the options that most tests vary.
inline SurfaceMesh phantom(PhantomKind kind, bool open_ends, double voxel, double noise = 0,
                           PhantomTruth* truth = nullptr) {
  PhantomOptions o;
  o.kind = kind;
  o.open_ends = open_ends;
  o.voxel = voxel;
  o.noise = noise;
  return phantom(o, truth);
}

/// The options of the noisy bifurcation: 3 openings, genus 0, voxel noise
/// 0.3, voxel size `voxel`.
inline PhantomOptions noisy_bifurcation_options(double voxel) {
  PhantomOptions o;
  o.kind = PhantomKind::kBifurcation;
  o.voxel = voxel;
  o.noise = 0.3;
  return o;
}

/// The noisy bifurcation phantom (open ends).
inline SurfaceMesh noisy_bifurcation(double voxel, PhantomTruth* truth = nullptr) {
  return phantom(noisy_bifurcation_options(voxel), truth);
}

/// A capped model: the noisy bifurcation with its three cut ends closed by
/// flat caps (closed, genus 0).
inline SurfaceMesh flat_capped_bifurcation(double voxel, PhantomTruth* truth = nullptr) {
  PhantomOptions o = noisy_bifurcation_options(voxel);
  o.flat_caps = true;
  return phantom(o, truth);
}

/// A capped model whose caps have `shape`: the bifurcation (or `kind`)
/// with its cut ends closed by flat caps, fans around a lifted apex or
/// domes (closed, genus 0).
inline SurfaceMesh capped_phantom(PhantomCapShape shape, double voxel, double noise,
                                  PhantomTruth* truth = nullptr,
                                  PhantomKind kind = PhantomKind::kBifurcation) {
  PhantomOptions o;
  o.kind = kind;
  o.voxel = voxel;
  o.noise = noise;
  o.flat_caps = true;
  o.cap_shape = shape;
  return phantom(o, truth);
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

/// The values of `per_vertex` at the vertices just inside an opening: 0.3
/// to 0.8 model units in from its plane (the rim itself has no closing
/// ball) and within two radii R of its centroid.
inline std::vector<double> rim_band_values(const SurfaceMesh& m, const Opening& op, double R,
                                           const std::vector<double>& per_vertex) {
  std::vector<double> near;
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    double along = 0, dist2 = 0;
    for (size_t k = 0; k < 3; ++k) {
      const double x = m.points[3 * v + k] - op.centroid[k];
      along += x * op.normal[k];
      dist2 += x * x;
    }
    if (along < -0.3 && along > -0.8 && dist2 < 4 * R * R) near.push_back(per_vertex[v]);
  }
  return near;
}

}  // namespace vm::testing
