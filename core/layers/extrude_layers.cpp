// Boundary-layer extrusion driver (Marchandise et al., section 2.2; phases as
// listed in extrude_layers.h): checks, openings, directions, thickness with
// gap limit, validity and verification rounds, construction, statistics.
#include "core/layers/extrude_layers.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "core/geom/closest_point.h"
#include "core/layers/layer_columns.h"
#include "core/layers/layer_directions.h"
#include "core/layers/layer_gap.h"
#include "core/layers/layer_geometry.h"
#include "core/layers/layer_thickness.h"
#include "core/layers/layer_validity.h"
#include "core/layers/layer_verify.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"
#include "core/mesh/surface_distance.h"
#include "core/quality/triangle_quality.h"
#include "core/surface/cap_openings.h"
#include "core/util/stage_timer.h"

namespace vm {
using namespace layers;  // NOLINT: the layer stage's own vector helpers

namespace {

constexpr double kMinFactor = 1e-3;
// Columns are lengthened for their lean by at most 1 / kMinLean.
constexpr double kMinLean = 0.7;
constexpr double kIntersectionShrink = 0.7;

std::string where(const std::vector<double>& pts, int32_t v) {
  const Vec3 p = at(pts, v);
  std::ostringstream s;
  s.precision(6);
  s << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return s.str();
}

Status check_spec(const LayerSpec& s) {
  if (!(s.gap_fraction > 0 && s.gap_fraction <= 0.5))
    return Status::Error("gap_fraction must be in (0, 0.5]");
  if (!(s.min_volume_ratio > 0 && s.min_volume_ratio < 1))
    return Status::Error("min_volume_ratio must be in (0, 1)");
  if (!(s.min_front_quality_ratio >= 0 && s.min_front_quality_ratio < 1))
    return Status::Error("min_front_quality_ratio must be in [0, 1)");
  if (!(s.gradation > 0) || !std::isfinite(s.gradation))
    return Status::Error("gradation must be > 0");
  if (s.smoothing_passes < 0) return Status::Error("smoothing_passes must be >= 0");
  if (s.max_rounds < 1) return Status::Error("max_rounds must be >= 1");
  return Status::Ok();
}

// Phase 0: the wall's structure (indices, manifold, orientation, every
// vertex used).
Status check_wall(const SurfaceMesh& wall, const TriangleAdjacency& adj) {
  if (Status s = check_manifold_oriented(wall, adj); !s.ok()) return s;
  for (size_t v = 0; v < wall.num_vertices(); ++v)
    if (adj.star_offsets[v] == adj.star_offsets[v + 1])
      return Status::Error("wall vertex " + std::to_string(v) + " " +
                           where(wall.points, int32_t(v)) + " is in no triangle");
  return Status::Ok();
}

// Signed volume of the wall closed by a fan on each opening (origin of its
// plane): positive for an outward-facing wall.
double fan_closed_volume(const SurfaceMesh& wall, const std::vector<LayerOpening>& ops) {
  const BoundingBox box = bounding_box(wall.points);
  const Vec3 o = {0.5 * (box.min[0] + box.max[0]), 0.5 * (box.min[1] + box.max[1]),
                  0.5 * (box.min[2] + box.max[2])};
  auto det = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    return dot(a - o, cross(b - o, c - o));
  };
  double v6 = 0;
  for (size_t t = 0; t < wall.num_triangles(); ++t) {
    const int32_t* f = &wall.triangles[3 * t];
    v6 += det(at(wall.points, f[0]), at(wall.points, f[1]), at(wall.points, f[2]));
  }
  for (const LayerOpening& op : ops)
    for (size_t i = 0; i < op.rim.size(); ++i)
      v6 += det(op.origin, at(wall.points, op.rim[(i + 1) % op.rim.size()]),
                at(wall.points, op.rim[i]));
  return v6 / 6;
}

}  // namespace

Result<LayerMesh> extrude_layers(const SurfaceMesh& wall_in, const std::vector<double>& radius,
                                 const LayerSpec& spec, LayerStats* stats_out) {
  using R = Result<LayerMesh>;
  const auto t_start = StageClock::now();
  LayerStats stats;
  const size_t nv = wall_in.num_vertices(), nt = wall_in.num_triangles();

  // Phase 0: checks.
  if (Status s = check_spec(spec); !s.ok()) return s;
  auto requested_or = requested_thickness(spec, radius, nv);
  if (!requested_or.ok()) return requested_or.status();
  const std::vector<double> requested = std::move(requested_or).value();
  if (nt == 0) return R::Error("the wall has no triangle");
  if (wall_in.triangles.size() % 3 != 0 || wall_in.points.size() % 3 != 0)
    return R::Error("the wall's arrays are not whole triangles / points");
  for (size_t t = 0; t < nt; ++t) {
    const int32_t* f = &wall_in.triangles[3 * t];
    for (int k = 0; k < 3; ++k)
      if (f[k] < 0 || size_t(f[k]) >= nv) return R::Error("a wall triangle index is out of range");
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2])
      return R::Error("wall triangle " + std::to_string(t) + " repeats a vertex");
  }
  if (int64_t(nv) * (spec.layers + 1) >= int64_t(INT32_MAX))
    return R::Error("too many points for 32-bit indices");
  const TriangleAdjacency adj = build_adjacency(wall_in);
  if (Status s = check_wall(wall_in, adj); !s.ok()) return s;

  // Phase 1: openings, their planes, rims onto the planes.
  auto t0 = StageClock::now();
  SurfaceMesh wall = wall_in;
  std::vector<LayerOpening> openings;
  std::vector<OpeningPlane> planes;
  std::vector<int32_t> on_opening(nv, -1);
  for (auto& loop : boundary_loops(wall_in, adj)) {
    for (int32_t v : loop) {
      if (on_opening[size_t(v)] >= 0)
        return R::Error("the openings at " + where(wall.points, v) + " share a vertex");
      on_opening[size_t(v)] = int32_t(openings.size());
    }
    if (loop.size() < 3)
      return R::Error("the opening at " + where(wall.points, loop[0]) +
                      " has fewer than 3 rim vertices");
    auto plane = fit_opening_plane(wall_in.points, loop);
    if (!plane.ok()) return R::Error("" + plane.message());
    LayerOpening op;
    op.origin = plane.value().origin;
    op.normal = plane.value().normal;
    op.e1 = plane.value().e1;
    op.e2 = plane.value().e2;
    op.rim = std::move(loop);
    for (size_t i = 0; i < op.rim.size(); ++i)
      put(wall.points, op.rim[i],
          plane.value().at(plane.value().uv[2 * i], plane.value().uv[2 * i + 1]));
    openings.push_back(std::move(op));
    planes.push_back(std::move(plane).value());
  }
  if (!(fan_closed_volume(wall, openings) > 0))
    return R::Error(
        "the wall faces inward (the volume it encloses is negative): orient it outward");
  const VertexRings rings = vertex_rings(wall, adj);

  // Phase 2: directions.
  auto dirs_or =
      layer_directions(wall, adj, rings, openings, spec.outward, spec.smoothing_passes, requested);
  if (!dirs_or.ok()) return dirs_or.status();
  const LayerDirections dirs = std::move(dirs_or).value();
  stats.min_visibility = dirs.min_visibility;
  stats.seconds_directions = seconds_since(t0);

  // Phase 2b: column lengths. A column leaning from the normals of its
  // wall triangles, or standing in a faceted hollow or crease, ends closer
  // to the wall than its length; it is lengthened (at most to 1 / kMinLean
  // times) until its end is at the requested distance from its star's
  // triangles, so the layer's height measured from the wall is the
  // requested one.
  std::vector<int32_t> star_offsets(nv + 1, 0), star_tris(3 * nt);
  for (int32_t v : wall.triangles) ++star_offsets[size_t(v) + 1];
  for (size_t v = 0; v < nv; ++v) star_offsets[v + 1] += star_offsets[v];
  {
    std::vector<int32_t> fill(star_offsets.begin(), star_offsets.end() - 1);
    for (size_t t = 0; t < nt; ++t)
      for (int c = 0; c < 3; ++c)
        star_tris[size_t(fill[size_t(wall.triangles[3 * t + size_t(c)])]++)] = int32_t(t);
  }
  std::vector<double> column(requested);
  for (size_t v = 0; v < nv && spec.lean_compensation; ++v) {
    const Vec3 x = at(wall.points, int32_t(v)), d = at(dirs.direction, int32_t(v));
    for (int iter = 0; iter < 3; ++iter) {
      const Vec3 p = x + column[v] * d;
      double d2 = column[v] * column[v];
      for (int32_t i = star_offsets[v]; i < star_offsets[v + 1]; ++i) {
        const int32_t* tv = &wall.triangles[3 * size_t(star_tris[size_t(i)])];
        double q[3];
        d2 = std::min(d2, closest_point_on_triangle(p.data(), &wall.points[3 * size_t(tv[0])],
                                                    &wall.points[3 * size_t(tv[1])],
                                                    &wall.points[3 * size_t(tv[2])], q));
      }
      const double reach = std::sqrt(d2);
      if (!(reach > 0) || reach >= 0.999 * requested[v]) break;
      column[v] = std::min(column[v] * requested[v] / reach, requested[v] / kMinLean);
    }
  }

  // Phase 3: gap limit.
  t0 = StageClock::now();
  const std::vector<double> fraction = layer_fractions(spec);
  std::vector<double> cosine(nv), needed(nv);
  for (size_t v = 0; v < nv; ++v) {
    cosine[v] = std::max(0.1, dot(at(dirs.direction, int32_t(v)), at(dirs.normal, int32_t(v))));
    needed[v] = column[v] / (2 * spec.gap_fraction * cosine[v]);
  }
  const std::vector<double> ball = empty_ball_radius(wall, dirs.normal, needed);
  std::vector<double> factor(nv, 1.0);
  for (size_t v = 0; v < nv; ++v) {
    if (!(ball[v] < needed[v])) continue;  // the ball of the needed size is empty
    const double limit = 2 * spec.gap_fraction * ball[v] * cosine[v];
    if (limit < column[v]) {
      factor[v] = std::max(kMinFactor, limit / column[v]);
      ++stats.limited_by_gap;
    }
  }
  grade_reduction(wall, rings, column, spec.gradation, kMinFactor, factor);
  stats.seconds_gap = seconds_since(t0);

  // Phases 4-5: validity and verification rounds.
  const LayerValidity validity(wall, dirs, column, fraction, spec.outward, spec.min_volume_ratio,
                               spec.min_front_quality_ratio);
  const LayerColumns cols(wall, dirs.direction, column, fraction, planes, openings,
                          dirs.opening_of);
  std::vector<uint8_t> by_validity(nv, 0), by_intersection(nv, 0);
  bool valid = false;
  size_t failing = 0, crossing = 0;
  for (int round = 1; round <= spec.max_rounds && !valid; ++round) {
    stats.rounds = round;
    t0 = StageClock::now();
    failing = validity.shrink_invalid(factor, by_validity, &stats.min_volume_ratio);
    if (failing > 0) grade_reduction(wall, rings, column, spec.gradation, kMinFactor, factor);
    stats.seconds_validity += seconds_since(t0);
    if (failing > 0) continue;
    if (!spec.verify_intersections) {
      valid = true;
      break;
    }
    t0 = StageClock::now();
    const std::vector<int32_t> involved =
        layer_intersections(wall, cols, factor, spec.layers, openings, spec.outward);
    stats.seconds_verify += seconds_since(t0);
    crossing = involved.size();
    if (involved.empty()) {
      valid = true;
      break;
    }
    for (int32_t v : involved) {
      factor[size_t(v)] = std::max(kMinFactor, factor[size_t(v)] * kIntersectionShrink);
      by_intersection[size_t(v)] = 1;
    }
    grade_reduction(wall, rings, column, spec.gradation, kMinFactor, factor);
  }
  if (!valid && spec.lean_compensation) {  // retry with columns of the requested length
    LayerSpec plain = spec;
    plain.lean_compensation = false;
    return extrude_layers(wall_in, radius, plain, stats_out);
  }
  if (!valid) {
    std::string what =
        failing > 0 ? std::to_string(failing) +
                          " wall triangles still have "
                          "invalid prisms"
                    : std::to_string(crossing / 2) + " columns still make the front intersect";
    // Where: the failing triangles' centroids (a few), else the columns'.
    Remedy remedy{"no_layers", {}, 0};
    for (size_t t = 0; t < nt && failing > 0 && remedy.places.size() < 32; ++t) {
      const auto f = validity.corner_factors(t, factor);
      if (validity.score(t, f.data()) >= 1) continue;
      const int32_t* c = &wall.triangles[3 * t];
      remedy.places.push_back(
          (1.0 / 3) * (at(wall.points, c[0]) + at(wall.points, c[1]) + at(wall.points, c[2])));
    }
    if (failing == 0)
      for (int32_t v : layer_intersections(wall, cols, factor, spec.layers, openings, spec.outward))
        if (remedy.places.size() < 32) remedy.places.push_back(at(wall.points, v));
    return Status::Error("no valid layer after " + std::to_string(spec.max_rounds) +
                         " rounds of shrinking (" + what + ")")
        .WithRemedy(std::move(remedy));
  }
  for (size_t v = 0; v < nv; ++v) {
    stats.limited_by_validity += by_validity[v];
    stats.limited_by_intersection += by_intersection[v];
  }

  // Phase 6: construction.
  LayerMesh m;
  m.layers = spec.layers;
  m.outward = spec.outward;
  m.wall_vertices = nv;
  m.wall_triangles = nt;
  m.directions = dirs.direction;
  m.requested_thickness = requested;
  m.factor = factor;
  m.fraction = fraction;
  m.thickness.resize(nv);
  for (size_t v = 0; v < nv; ++v) m.thickness[v] = factor[v] * column[v];
  const size_t n_layers = size_t(spec.layers);
  m.points.resize(3 * nv * (n_layers + 1));
  std::copy(wall.points.begin(), wall.points.end(), m.points.begin());
  for (size_t k = 1; k <= n_layers; ++k)
    for (size_t v = 0; v < nv; ++v)
      put(m.points, m.layer_vertex(int32_t(v), int(k)), cols.point(int32_t(v), k, factor[v]));
  build_prisms_and_front(m, wall.triangles);
  for (LayerOpening& op : openings) {
    op.columns.reserve(op.rim.size() * (n_layers + 1));
    for (int32_t v : op.rim)
      for (size_t k = 0; k <= n_layers; ++k) op.columns.push_back(m.layer_vertex(v, int(k)));
  }
  m.openings = std::move(openings);

  // Statistics.
  t0 = StageClock::now();
  std::vector<double> vertex_area(nv, 0.0);
  double qmin = 1, qsum = 0, wmin = 1;
  for (size_t t = 0; t < nt; ++t) {
    const int32_t* f = &wall.triangles[3 * t];
    const Vec3 a = at(wall.points, f[0]), b = at(wall.points, f[1]), c = at(wall.points, f[2]);
    const double area = 0.5 * norm(cross(b - a, c - a));
    for (int k = 0; k < 3; ++k) vertex_area[size_t(f[k])] += area / 3;
    stats.wall_area += area;
    wmin = std::min(wmin, triangle_gamma(a.data(), b.data(), c.data()));
    const int32_t* g = &m.front[3 * t];
    const double q = triangle_gamma(&m.points[3 * size_t(g[0])], &m.points[3 * size_t(g[1])],
                                    &m.points[3 * size_t(g[2])]);
    qmin = std::min(qmin, q);
    qsum += q;
  }
  stats.front_quality_min = qmin;
  stats.front_quality_mean = qsum / double(nt);
  stats.wall_quality_min = wmin;
  double fsum = 0, reduced_fsum = 0, within = 0;
  stats.min_factor = 1;
  for (size_t v = 0; v < nv; ++v) {
    const double a = vertex_area[v];
    fsum += a * factor[v];
    stats.min_factor = std::min(stats.min_factor, factor[v]);
    if (factor[v] < 0.999) stats.reduced_area += a, reduced_fsum += a * factor[v];
    if (factor[v] >= 0.9) within += a;
  }
  stats.mean_factor = fsum / stats.wall_area;
  stats.reduced_area_fraction = stats.reduced_area / stats.wall_area;
  stats.mean_reduced_factor = stats.reduced_area > 0 ? reduced_fsum / stats.reduced_area : 1;
  stats.thickness_within_10pct = within / stats.wall_area;
  if (spec.measure) {
    const TriangleBvh bvh = build_triangle_bvh(wall);
    double first_in = 0, total_in = 0, first_sum = 0, total_sum = 0;
    for (size_t v = 0; v < nv; ++v) {
      const double a = vertex_area[v];
      const double* p1 = &m.points[3 * size_t(m.layer_vertex(int32_t(v), 1))];
      const double* pn = &m.points[3 * size_t(m.layer_vertex(int32_t(v), spec.layers))];
      const double r1 =
          closest_surface_point(wall, bvh, p1).distance / (fraction[1] * requested[v]);
      const double rn = closest_surface_point(wall, bvh, pn).distance / requested[v];
      first_sum += a * r1;
      total_sum += a * rn;
      first_in += std::abs(r1 - 1) <= 0.1 ? a : 0;
      total_in += std::abs(rn - 1) <= 0.1 ? a : 0;
    }
    stats.measured_first_within_10pct = first_in / stats.wall_area;
    stats.measured_total_within_10pct = total_in / stats.wall_area;
    stats.measured_first_mean_ratio = first_sum / stats.wall_area;
    stats.measured_total_mean_ratio = total_sum / stats.wall_area;
  }
  stats.seconds_measure = seconds_since(t0);
  stats.seconds_total = seconds_since(t_start);
  if (stats_out) *stats_out = stats;
  return m;
}

}  // namespace vm
