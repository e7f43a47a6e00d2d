// Data of the boundary-layer stage (docs/ARCHITECTURE.md, stage 4; Marchandise
// et al., section 2.2: an advancing-layer mesh grown from the remeshed wall,
// inward for the viscous layer, outward for the vessel wall, prisms split
// into tetrahedra). Plain structs; the algorithm is in extrude_layers.h.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vm {

/// What to grow. Thickness per wall vertex v: T(v) = thickness_fraction *
/// R(v), or, when first_height > 0, the absolute series first_height *
/// growth^k summed over the layers (the same everywhere). Layer heights
/// within a column follow growth: h_k = h_1 growth^(k-1) (uniform for 1).
struct LayerSpec {
  int layers = 4;                   ///< N >= 1
  double thickness_fraction = 0.2;  ///< of the local vessel radius R(x), > 0
  double first_height = 0;          ///< > 0: absolute first-layer height (model units)
  double growth = 1.0;              ///< ratio of consecutive layer heights, > 0
  bool outward = false;             ///< false: viscous layer (into the lumen); true: vessel wall

  /// Laplacian passes smoothing the directions on the unit sphere.
  int smoothing_passes = 5;
  /// Gap limit: the total thickness is at most gap_fraction times the
  /// diameter of the largest empty ball tangent at the vertex on the layer
  /// side (the local gap between facing walls or branches, layer_gap.h),
  /// times cos(direction, normal): two facing fronts then keep at least
  /// 1 - 2 gap_fraction of the gap between them.
  double gap_fraction = 0.4;
  /// Local validity margin: every sub-tetrahedron of every prism slice has
  /// 6 V >= min_volume_ratio * 2 A h (A the wall triangle's area, h the
  /// slice's smallest column height; 2 A h is 6 V of each third of an
  /// upright prism), lowered to half the triangle's worst visibility
  /// (direction . normal) where that is smaller.
  double min_volume_ratio = 0.1;
  /// The front triangle's gamma_k must stay >= this fraction of its wall
  /// triangle's (the front is the core mesher's boundary).
  double min_front_quality_ratio = 0.5;
  /// Largest slope of the thickness next to a reduced vertex (thickness per
  /// unit length along the wall): a reduction ramps in over (requested -
  /// achieved) / gradation, and leaves the rest untouched.
  double gradation = 0.5;
  /// Rounds of shrink-and-verify before giving up.
  int max_rounds = 16;
  /// Exact check that wall, front and rings do not intersect (with all
  /// prisms positive this proves the layer is embedded, see extrude_layers.h).
  bool verify_intersections = true;
  /// Lengthen each column for its lean from its wall triangles, so heights
  /// measured from a faceted or creased wall are the requested ones; when
  /// no valid layer is found that way (a raw, jagged wall), the stage
  /// retries with columns of the requested length.
  bool lean_compensation = true;
  /// Also measure the heights as distances of the first layer's and the
  /// front's points to the wall surface (LayerStats::measured_*; two
  /// closest-point queries per vertex, about a third of the stage's time,
  /// so off by default).
  bool measure = false;
};

/// One opening (boundary loop of the wall) and its column of layer points.
struct LayerOpening {
  /// The cap plane (cap_openings.h fit_opening_plane): origin, unit normal out of
  /// the lumen, in-plane frame e1 x e2 = normal.
  std::array<double, 3> origin{}, normal{}, e1{}, e2{};
  /// Wall vertex ids in the order of the wall's boundary half-edges
  /// (mesh/boundary_loops.h), i.e. clockwise around `normal`.
  std::vector<int32_t> rim;
  /// (layers + 1) ids per rim vertex: columns[(layers + 1) i + k] is the
  /// point of layer k above rim[i] (k = 0: the wall vertex itself). All lie
  /// in the plane.
  std::vector<int32_t> columns;
};

/// The layer mesh. With nv wall vertices and nt wall triangles:
/// - points: 3 doubles per vertex; ids [0, nv) are the wall's (rim vertices
///   moved onto their opening planes exactly as cap_openings moves them,
///   others unchanged), then layer k = 1..N at [k nv, (k + 1) nv): vertex
///   k nv + v lies above wall vertex v.
/// - prisms: 6 ids per prism, layer-major (prism k nt + t is wall triangle
///   t's slice between layers k and k + 1), VolumeMesh order: 0-1-2 on the
///   layer nearer the wall, 3-4-5 above them, every sub-tetrahedron of
///   split_prism positive. Inward: bottom = wall triangle reversed; outward:
///   bottom = wall triangle.
/// - front: 3 ids per wall triangle, the last layer's surface with the
///   wall's triangle order and orientation (normals out of the vessel).
struct LayerMesh {
  int layers = 0;
  bool outward = false;
  size_t wall_vertices = 0;
  size_t wall_triangles = 0;
  std::vector<double> points;
  std::vector<int32_t> prisms;
  std::vector<int32_t> front;
  std::vector<LayerOpening> openings;
  /// Per wall vertex: unit direction of its column (3 doubles), the
  /// requested total thickness, the achieved column length (along the
  /// direction; lengthened for the column's lean, see extrude_layers.h) and
  /// the reduction factor (1 where nothing was reduced).
  std::vector<double> directions;
  std::vector<double> requested_thickness;
  std::vector<double> thickness;
  std::vector<double> factor;
  /// Cumulative height fractions of the layers: point k of a column is
  /// wall + fraction[k] * thickness * direction; fraction[0] = 0,
  /// fraction[N] = 1.
  std::vector<double> fraction;

  /// Id of the layer-k point above wall vertex v (k in [0, layers]).
  int32_t layer_vertex(int32_t v, int k) const { return int32_t(size_t(k) * wall_vertices) + v; }
  size_t num_vertices() const { return points.size() / 3; }
  size_t num_prisms() const { return prisms.size() / 6; }
};

/// Fills m.prisms and m.front (layouts above) from the wall's triangles
/// (3 ids each, outward): m.layers, m.outward and m.wall_vertices must be
/// set; the prism bottoms are the triangles turned to face the layer side.
inline void build_prisms_and_front(LayerMesh& m, const std::vector<int32_t>& triangles) {
  const size_t nt = triangles.size() / 3, n_layers = size_t(m.layers);
  m.prisms.clear();
  m.prisms.reserve(6 * nt * n_layers);
  for (size_t k = 0; k < n_layers; ++k)
    for (size_t t = 0; t < nt; ++t) {
      const int32_t* f = &triangles[3 * t];
      const int32_t b[3] = {f[0], m.outward ? f[1] : f[2], m.outward ? f[2] : f[1]};
      for (int j = 0; j < 3; ++j) m.prisms.push_back(m.layer_vertex(b[j], int(k)));
      for (int j = 0; j < 3; ++j) m.prisms.push_back(m.layer_vertex(b[j], int(k + 1)));
    }
  m.front.resize(3 * nt);
  for (size_t i = 0; i < 3 * nt; ++i) m.front[i] = m.layer_vertex(triangles[i], m.layers);
}

/// What the stage did (areas are wall areas: each vertex owns a third of
/// its triangles' areas).
struct LayerStats {
  double wall_area = 0;
  /// Wall area whose thickness was reduced (factor < 0.999), and as a
  /// fraction of wall_area.
  double reduced_area = 0, reduced_area_fraction = 0;
  /// Smallest factor, area-weighted mean factor over all the wall and over
  /// the reduced part.
  double min_factor = 1, mean_factor = 1, mean_reduced_factor = 1;
  /// Wall vertices limited by each cause (a vertex may count in several).
  size_t limited_by_gap = 0, limited_by_validity = 0, limited_by_intersection = 0;
  /// Fraction of wall area whose achieved total thickness (along the
  /// column) is within 10% of the requested one.
  double thickness_within_10pct = 0;
  /// With LayerSpec::measure: the first layer's and the front's distance to
  /// the wall surface (closest point) over their requested heights: the
  /// fraction of wall area within 10%, and the area-weighted mean ratio.
  double measured_first_within_10pct = 0, measured_total_within_10pct = 0;
  double measured_first_mean_ratio = 0, measured_total_mean_ratio = 0;
  /// gamma_k of the front triangles (min, mean) and of the wall's (min).
  double front_quality_min = 0, front_quality_mean = 0, wall_quality_min = 0;
  /// Smallest 6V / (2 A h) over all sub-tetrahedra (see min_volume_ratio;
  /// d . n for an upright-but-sheared prism).
  double min_volume_ratio = 0;
  /// Smallest direction . triangle normal over every wall triangle corner.
  double min_visibility = 0;
  int rounds = 0;  ///< shrink/verify rounds used
  double seconds_directions = 0, seconds_gap = 0, seconds_validity = 0, seconds_verify = 0,
         seconds_measure = 0, seconds_total = 0;
};

}  // namespace vm
