// Planar caps on the openings of a remeshed vessel wall (Marchandise et al.,
// section 2: each inlet/outlet is closed by a planar surface so the lumen is
// a closed domain with flat boundary sections for the flow conditions; the
// caps are meshed with the 2D mesher of section 3 / Table 1, "Frontal").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/mesh2d/delaunay_refinement.h"
#include "core/util/result.h"

namespace vm {

struct CapOptions {
  /// Which cap is named `inlet`: an index into the caps sorted by decreasing
  /// area (0 = the largest). Must be < the number of openings when there is
  /// at least one; ignored for a closed surface.
  int inlet_index = 0;
  /// Options of the frontal-Delaunay mesher of each cap.
  RefinementOptions refinement;
  /// Passes of Delaunay flips and smoothing of each cap (mesh2d/optimize2d.h).
  int optimize_passes = 5;
  /// Distance from the rim, in local rim edge lengths, over which the cap
  /// size blends from the rim edge lengths to the requested sizes (> 0).
  double blend_lengths = 3.0;
};

/// One cap, i.e. one closed opening.
struct CapInfo {
  std::string name;  ///< "inlet", "outlet_1", "outlet_2", ...
  int32_t tag = 0;   ///< its value in CappedSurface::triangle_tag (1 inlet, 2.. outlets)
  double area = 0;   ///< area of the planar cap (model units squared)
  /// Area centroid of the planar cap (x y z).
  std::array<double, 3> centroid{};
  /// Unit normal of the cap plane, pointing out of the lumen.
  std::array<double, 3> normal{};
  double perimeter = 0;  ///< length of the rim after projection
  /// The rim: output vertex indices (the wall's), in the order of the wall's
  /// boundary half-edges (mesh/boundary_loops.h); the cap traverses it in
  /// reverse.
  std::vector<int32_t> rim;
  size_t interior_vertices = 0;  ///< new vertices inside the cap
  size_t first_triangle = 0;     ///< the cap's triangles in the output: [first, first + triangles)
  size_t triangles = 0;
  /// Largest distance a rim vertex moved to reach the fitted plane: how far
  /// the opening was from planar (the caller may warn when it is large
  /// compared with the rim edges).
  double max_projection_distance = 0;
  /// Wall triangles at the rim whose normal turned by more than 90 degrees
  /// when the rim moved onto the plane (0 unless the opening was far from
  /// planar).
  size_t flipped_wall_triangles = 0;
  double quality_min = 0, quality_mean = 0;  ///< gamma_k of the cap's triangles
};

/// The least-squares plane of one opening (the rim-plane fit cap_openings
/// uses, exported so the boundary layers place their rim columns in the same
/// planes).
struct OpeningPlane {
  std::array<double, 3> origin{};  ///< weighted centroid of the rim polyline
  std::array<double, 3> normal{};  ///< unit, out of the lumen
  /// Unit in-plane frame, e1 x e2 = normal (counterclockwise in (u, v) faces
  /// out of the lumen); e1 points toward the first rim vertex.
  std::array<double, 3> e1{}, e2{};
  /// The rim in plane coordinates: 2 per loop vertex (u, v), loop order.
  std::vector<double> uv;
  /// Largest distance of a rim vertex from the plane (before projection).
  double max_projection = 0;

  /// The plane point with coordinates (u, v): origin + u e1 + v e2. This is
  /// the exact arithmetic cap_openings uses to move rim vertex i onto the
  /// plane (u, v = uv[2i], uv[2i + 1]), so a caller using it gets the same
  /// doubles.
  std::array<double, 3> at(double u, double v) const {
    std::array<double, 3> p;
    for (int k = 0; k < 3; ++k) p[k] = origin[k] + u * e1[k] + v * e2[k];
    return p;
  }
};

/// Fits the plane of the opening whose rim is `loop` (vertex indices into
/// `points`, 3 doubles per vertex, in the order of the wall's boundary
/// half-edges as mesh/boundary_loops.h lists them, >= 3 vertices): the
/// least-squares plane through the loop points weighted by their share of
/// the loop length, normal oriented out of the lumen (against the loop's
/// vector area, the wall being outward oriented). Errors: a rim of zero
/// length, collinear rim vertices. The rim is not checked for simplicity.
Result<OpeningPlane> fit_opening_plane(const std::vector<double>& points,
                                       const std::vector<int32_t>& loop);

/// The wall closed by its caps.
struct CappedSurface {
  /// Points: the wall's (rim vertices moved onto their planes, all others
  /// unchanged, same indices) followed by the caps' interior points, cap
  /// after cap in tag order. Triangles: the wall's (same order and corners)
  /// followed by each cap's, in tag order. Closed and outward oriented.
  SurfaceMesh mesh;
  /// One tag per triangle: 0 wall, 1 inlet, 2.. outlet_1..k.
  std::vector<int32_t> triangle_tag;
  /// caps[i] has tag i + 1: the inlet first, then the outlets by decreasing
  /// area.
  std::vector<CapInfo> caps;
  size_t wall_vertices = 0;
  size_t wall_triangles = 0;
};

/// Closes every opening (boundary loop) of `wall` by a planar cap.
///
/// For each loop: the plane is the least-squares fit through the loop points
/// weighted by their share of the loop's length (the centroid of the
/// polyline and the eigenvector of the smallest eigenvalue of its covariance,
/// so uneven rim sampling does not tilt it), its normal oriented out of the
/// lumen (against the loop's vector area, the wall being outward oriented).
/// Every rim vertex is moved onto the plane along the normal (the wall keeps
/// it: caps and wall share the rim vertices exactly, no point is added on the
/// rim). The rim polygon, in plane coordinates, is meshed by frontal-Delaunay
/// (mesh2d/frontal_delaunay.h) then optimized (mesh2d/optimize2d.h), and the
/// planar points are mapped back isometrically, so the cap is planar up to
/// rounding.
///
/// Size in the cap: two Shepard (inverse squared distance, weighted by rim
/// edge length) interpolations of rim values are blended, h_rim of the local
/// rim edge lengths (mean of the two rim edges at a vertex, so the triangles
/// on the rim fit it) and h_target of `vertex_size` at the rim vertices; the
/// weight of h_target rises smoothly (smoothstep) from 0 on the rim to 1 at
/// `blend_lengths` rim edge lengths from the nearest rim vertex. For a rim
/// sampled at the requested size (as the remesher leaves it) both agree.
///
/// Caps are ordered by decreasing area (areas within 1e-9 of the largest
/// are ties, broken by the smallest rim vertex index); `options.inlet_index`
/// picks the inlet, the others are outlet_1..k in that order.
///
/// Inputs: `wall` manifold, consistently outward oriented, openings that are
/// simple loops not sharing a vertex; `vertex_size` one target edge length
/// (> 0, model units) per wall vertex, only read at rim vertices, or empty to
/// use the rim edge lengths alone. A closed wall gives no cap (all tags 0).
///
/// Errors: a size vector of the wrong length or a non-positive size, a non-
/// manifold or inconsistently oriented wall, an inward-facing wall (the
/// capped surface would enclose a negative volume), a vertex on two
/// openings, a rim with fewer than 3 vertices, a rim whose projection onto
/// its plane is not a simple polygon (self-intersecting, folded or
/// degenerate), a mesher failure, inlet_index out of range.
Result<CappedSurface> cap_openings(const SurfaceMesh& wall, const std::vector<double>& vertex_size,
                                   const CapOptions& options = {});

}  // namespace vm
