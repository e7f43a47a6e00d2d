// Local validity of boundary-layer prisms (Marchandise et al., section 2.2:
// "care is taken to produce elements of acceptable shape at sharp corners"):
// every sub-tetrahedron of every prism positive with a margin, and the front
// triangle still well shaped, as functions of per-vertex thickness factors;
// and the local shrink that restores validity by bisection on the factors.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/layers/layer_directions.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

/// The prism columns of a wall as functions of the factors: the layer-k
/// point of wall vertex v is wall[v] + fraction[k] * factor[v] *
/// requested[v] * direction[v]. Prism ids and splits are those of
/// LayerMesh (extrude_layers.h), so the tetrahedra checked are the ones the
/// output is split into.
class LayerValidity {
 public:
  /// All references must outlive the object. `fraction`: N + 1 cumulative
  /// layer fractions; min_volume_ratio and min_front_quality_ratio as in
  /// LayerSpec.
  LayerValidity(const SurfaceMesh& wall, const LayerDirections& dirs,
                const std::vector<double>& requested, const std::vector<double>& fraction,
                bool outward, double min_volume_ratio, double min_front_quality_ratio);

  /// Score of wall triangle t's column with factors f[0..2] at its corners
  /// (in the triangle's corner order): >= 1 when valid. It is the smaller of
  /// (6V / (2 A h)) / margin over its sub-tetrahedra (A the wall triangle's
  /// area, h the slice's smallest column height; the margin is min_volume_ratio, or half
  /// the worst visibility of the triangle from its corners' directions if
  /// smaller, so every triangle becomes valid for small enough factors) and
  /// gamma(front) / (min_front_quality_ratio gamma(wall)). When
  /// `volume_ratio` is given, it receives the smallest 6V / (2 A h).
  double score(size_t t, const double f[3], double* volume_ratio = nullptr) const;

  /// Factors of t's corners from the per-vertex array.
  std::array<double, 3> corner_factors(size_t t, const std::vector<double>& factor) const {
    const int32_t* v = &wall_.triangles[3 * t];
    return {factor[size_t(v[0])], factor[size_t(v[1])], factor[size_t(v[2])]};
  }

  /// For every triangle whose score is < 1, finds by bisection the largest
  /// level c for which capping its corners' factors at c makes it valid
  /// (the tallest columns come down first; a corner already below c keeps
  /// its factor, so repeated rounds do not push lowered corners down again
  /// just for standing next to taller ones), and lowers those corners to it
  /// (the smallest over the failing
  /// triangles at a vertex). Marks lowered vertices in `lowered` (one flag
  /// per wall vertex). Returns the number of failing triangles; when
  /// `min_ratio` is given it receives the smallest 6V / (2 A h) over all
  /// prisms with the factors as they were on entry.
  size_t shrink_invalid(std::vector<double>& factor, std::vector<uint8_t>& lowered,
                        double* min_ratio = nullptr) const;

 private:
  const SurfaceMesh& wall_;
  const LayerDirections& dirs_;
  const std::vector<double>& requested_;
  const std::vector<double>& fraction_;
  bool outward_;
  double min_front_quality_ratio_;
  std::vector<double> area_;    // per wall triangle
  std::vector<double> gamma_;   // per wall triangle
  std::vector<double> margin_;  // per wall triangle
  // Per wall triangle: its three sub-tetrahedra as local prism corners
  // (0-2 bottom, 3-5 top, bottom in prism order), the same in every slice.
  std::vector<std::array<uint8_t, 12>> split_;
};

}  // namespace vm
