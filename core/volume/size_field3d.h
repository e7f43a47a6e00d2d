// Volume size function of the tetrahedral fill (docs/
// ARCHITECTURE.md, stage 6: refinement to h(x) graded from the layer top to
// the core size):
//
//   h(x) = min(H, min_i (h_i + g |x - x_i|))
//
// over the boundary vertices x_i with their sizes h_i, H the core size (no
// cap when H = 0) and g the gradation. It is the largest g-Lipschitz
// function not above any h_i at x_i (nor above H anywhere): the mesh grows
// away from the surface at the rate g (a neighbor is at most (1 + g) times
// larger per unit of edge length), as the gradation-limited fields of
// Borouchaki, Hecht and Frey ("Mesh gradation control", IJNME 43, 1998).
//
// Evaluation is exact (no k-nearest approximation): a branch-and-bound
// search over a k-d tree whose nodes store their bounding box and the
// smallest size inside, so a node is skipped when min_h + g dist(x, box)
// cannot beat the best value found. An upper bound known by the caller
// (e.g. h(a) + g |x - a| from a nearby point a, valid since h is
// g-Lipschitz) makes the search prune from the start.
#pragma once

#include <cstdint>
#include <vector>

#include "core/geom/refine_sphere.h"
#include "core/util/result.h"

namespace vm {

struct VolumeSizeOptions {
  /// Core size H (model units): the cap of h. 0: no cap (pure gradation).
  double core_size = 0;
  /// Gradation g >= 0 (dimensionless): growth of h per unit distance.
  double gradation = 0.25;
  /// Local refinement (refine_sphere.h), graded at `gradation`.
  std::vector<RefineSphere> spheres;
};

class VolumeSizeField {
 public:
  VolumeSizeField() = default;

  /// points: 3 doubles per boundary vertex; sizes: one per vertex, finite and
  /// > 0 (model units). Errors: size mismatch, no point, non-finite
  /// coordinate, non-positive or non-finite size, negative or non-finite
  /// core size or gradation.
  static Result<VolumeSizeField> build(const std::vector<double>& points,
                                       const std::vector<double>& sizes,
                                       const VolumeSizeOptions& options = {});

  /// h(x), x 3 doubles.
  double operator()(const double* x) const { return eval(x, kNoBound); }

  /// h(x) given any upper_bound >= h(x) (a looser one is fine; infinity
  /// means none). Returns min(upper_bound, h(x)) exactly, i.e. h(x) when the
  /// bound is valid. With rel_tol > 0 (< 1) the search skips what cannot
  /// beat (1 - rel_tol) times the best value found, and the result r
  /// satisfies h(x) <= r <= h(x) / (1 - rel_tol) (when the bound is valid):
  /// inside a tube all the wall is at about the same distance from the
  /// axis, and the exact minimum must visit all of it.
  double eval(const double* x, double upper_bound, double rel_tol = 0) const;

  double core_size() const { return core_; }
  double gradation() const { return g_; }
  /// Smallest boundary size (min_i h_i, capped by H).
  double min_size() const { return min_size_; }
  size_t num_points() const { return pts_.size() / 3; }

  static constexpr double kNoBound = 1e300;

 private:
  struct Node {
    float lo[3], hi[3];  // bounding box, rounded outward
    int32_t begin, end;  // point range (leaves), else children at 2i+1, 2i+2
    double min_h;        // smallest size in the subtree (exact, so that a
                         // node can be pruned when it can only tie)
  };
  void build_node(int32_t node, int32_t begin, int32_t end);

  std::vector<double> pts_;   // 3 per point, in tree order
  std::vector<double> size_;  // per point, in tree order
  std::vector<Node> nodes_;   // implicit binary tree, root 0
  double core_ = 0, g_ = 0.25, min_size_ = 0;
  std::vector<RefineSphere> spheres_;
};

}  // namespace vm
