// Target edge length at the input vertices: uniform, radius-adaptive
// h = 2 pi R(x) / N (Marchandise et al., eq. 11), or curvature-adaptive,
// clamped and graded.
#pragma once

#include <limits>
#include <span>
#include <vector>

#include "core/geom/refine_sphere.h"
#include "core/mesh/surface_mesh.h"
#include "core/util/result.h"

namespace vm {

enum class SizeMode {
  kUniform,           ///< h = size everywhere
  kPerCircumference,  ///< h = 2 pi R(x) / per_circumference
};

struct SizeOptions {
  SizeMode mode = SizeMode::kPerCircumference;
  double size = 0;                ///< uniform h (model units), > 0 in that mode
  double per_circumference = 20;  ///< N, > 0 in that mode
  /// If > 0: h <= 2 pi / (curvature_points * kappa), kappa an estimate of
  /// the largest principal curvature at the vertex (twice the mean normal
  /// curvature along its edges: exact on a cylinder, twice too large on a
  /// sphere). In points per radian of turning; 0 = off.
  double curvature_points = 0;
  double size_min = 0;                                        ///< clamp (0 = none)
  double size_max = std::numeric_limits<double>::infinity();  ///< clamp
  /// Gradation: h may grow by at most this per unit length along the
  /// surface (|grad h| <= gradation; 0 = off).
  double gradation = 0.2;
  /// Local refinement (refine_sphere.h): h <= H inside each sphere, graded
  /// out of it, before the gradation phase.
  std::vector<RefineSphere> spheres;
};

/// One size per input vertex (num_vertices values, > 0). The radius comes
/// from vessel_radius (shrinking balls). Errors: non-positive or non-finite
/// parameters, min > max, an empty mesh.
Result<std::vector<double>> vertex_sizes(const SurfaceMesh& mesh, const SizeOptions& options);

/// The same with the local radius given (one per vertex, model units, as
/// vessel_radius gives it; used in the per-circumference mode only), for a
/// caller that also needs the radius (size_preview.h). Precondition:
/// radius.size() == mesh.num_vertices() in that mode.
Result<std::vector<double>> vertex_sizes(const SurfaceMesh& mesh, const SizeOptions& options,
                                         std::span<const double> radius);

/// Limits the growth of `h` (one size per vertex of `mesh`) to `gradation`
/// per unit length along the edges, lowering sizes only (0: no change).
void limit_gradation(const SurfaceMesh& mesh, std::vector<double>& h, double gradation);

}  // namespace vm
