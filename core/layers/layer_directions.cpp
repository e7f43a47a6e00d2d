// Boundary-layer directions (Marchandise et al., section 2.2, Gouraud
// normals; smoothing and visibility as in the advancing-layer literature:
// Garimella and Shephard, IJNME 49, 2000; Aubry and Lohner, IJNMF 2009) in
// the phases listed in layer_directions.h.
#include "core/layers/layer_directions.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/mesh/star_visibility.h"
#include "core/util/portable_math.h"

namespace vm {
using namespace layers;  // NOLINT: the layer stage's own vector helpers
namespace {

// Each direction is pushed until it sees every triangle of its star at
// direction . normal >= this: a prism's three columns then lie within 66
// degrees of its base triangle's normal, and so does the line through the
// centres of stacked prisms, which keeps finite-volume non-orthogonality
// below OpenFOAM's 70-degree limit at creases (0.3 allowed 72.5 degrees:
// 70.7 was measured on a coronary tree).
constexpr double kVisibilityTarget = 0.4;
constexpr double kVisibilityFloor = 0.02;

std::string where(const SurfaceMesh& m, int32_t v) {
  const Vec3 p = at(m.points, v);
  std::ostringstream s;
  s.precision(6);
  s << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return s.str();
}

Vec3 in_plane(const Vec3& d, const LayerOpening& op) {
  return dot(d, op.e1) * op.e1 + dot(d, op.e2) * op.e2;
}

// Phase 1: angle-weighted vertex normals and unit triangle normals, on the
// layer side (sign = -1 inward, +1 outward).
void gouraud_normals(const SurfaceMesh& m, double sign, std::vector<double>& vn,
                     std::vector<double>& tn) {
  vn.assign(m.points.size(), 0.0);
  tn.assign(3 * m.num_triangles(), 0.0);
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t* v = &m.triangles[3 * t];
    const Vec3 p[3] = {at(m.points, v[0]), at(m.points, v[1]), at(m.points, v[2])};
    const Vec3 n = normalized(sign * cross(p[1] - p[0], p[2] - p[0]));
    for (int d = 0; d < 3; ++d) tn[3 * t + size_t(d)] = n[d];
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = normalized(p[(k + 1) % 3] - p[k]), b = normalized(p[(k + 2) % 3] - p[k]);
      const double angle = pm::acos(std::clamp(dot(a, b), -1.0, 1.0));
      for (int d = 0; d < 3; ++d) vn[3 * size_t(v[k]) + size_t(d)] += angle * n[d];
    }
  }
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    const Vec3 n = normalized(at(vn, int32_t(v)));
    put(vn, int32_t(v), n);
  }
}

// Phase 2: the direction of a rim vertex, in its opening's plane: the
// normal's projection, or the rim polygon's in-plane normal (toward the
// inside of the rim for inward layers) when the projection is short or
// turns more than 60 degrees away from it.
Vec3 rim_direction(const SurfaceMesh& m, const LayerOpening& op, size_t i, const Vec3& normal,
                   bool outward) {
  const size_t n = op.rim.size();
  auto uv = [&](size_t j) {
    const Vec3 d = at(m.points, op.rim[j % n]) - op.origin;
    return std::array<double, 2>{dot(d, op.e1), dot(d, op.e2)};
  };
  const auto a = uv(i + n - 1), b = uv(i), c = uv(i + 1);
  // The rim runs clockwise around the normal: the inside is on the right.
  auto right = [](const std::array<double, 2>& p, const std::array<double, 2>& q) {
    const double du = q[0] - p[0], dv = q[1] - p[1], l = pm::hypot(du, dv);
    return l > 0 ? std::array<double, 2>{dv / l, -du / l} : std::array<double, 2>{0, 0};
  };
  const auto r1 = right(a, b), r2 = right(b, c);
  Vec3 inside = normalized((r1[0] + r2[0]) * op.e1 + (r1[1] + r2[1]) * op.e2);
  if (outward) inside = -1.0 * inside;
  const Vec3 proj = in_plane(normal, op);
  const Vec3 d = normalized(proj);
  if (norm(proj) > 0.3 && dot(d, inside) > 0.5) return d;
  return inside;
}

// Phase 4: see_star from d, kept in the opening's plane on a rim; returns
// the best direction found and its worst visibility.
std::pair<Vec3, double> make_visible(const TriangleAdjacency& adj, const std::vector<double>& tn,
                                     size_t v, Vec3 d, const LayerOpening* plane) {
  const int32_t first = adj.star_offsets[v];
  const double w = see_star(&adj.star[size_t(first)], adj.star_offsets[v + 1] - first, tn.data(),
                            d.data(), kVisibilityTarget, 40, [&](double* x) {
                              if (!plane) return;
                              const Vec3 p = in_plane({x[0], x[1], x[2]}, *plane);
                              x[0] = p[0], x[1] = p[1], x[2] = p[2];
                            });
  return {d, w};
}

}  // namespace

Result<LayerDirections> layer_directions(const SurfaceMesh& wall, const TriangleAdjacency& adj,
                                         const layers::VertexRings& rings,
                                         const std::vector<LayerOpening>& openings, bool outward,
                                         int passes, const std::vector<double>& reach) {
  const size_t nv = wall.num_vertices();
  LayerDirections out;
  gouraud_normals(wall, outward ? 1.0 : -1.0, out.normal, out.triangle_normal);

  // Phase 2: rim directions.
  out.opening_of.assign(nv, -1);
  std::vector<double>& dir = out.direction;
  dir = out.normal;
  for (size_t o = 0; o < openings.size(); ++o) {
    const LayerOpening& op = openings[o];
    for (size_t i = 0; i < op.rim.size(); ++i) {
      const int32_t v = op.rim[i];
      out.opening_of[size_t(v)] = int32_t(o);
      const Vec3 d = rim_direction(wall, op, i, at(out.normal, v), outward);
      if (!(norm(d) > 0.5))
        return Status::Error("no in-plane direction at rim vertex " + std::to_string(v) + " " +
                             where(wall, v) + " (degenerate rim)")
            .WithRemedy({"trim_end", {at(wall.points, v)}, 0});
      put(dir, v, d);
    }
  }

  // Phase 3: Laplacian smoothing on the sphere, rims held.
  std::vector<double> next = dir;
  for (int pass = 0; pass < passes; ++pass) {
    for (size_t v = 0; v < nv; ++v) {
      if (out.opening_of[v] >= 0) continue;
      Vec3 mean{0, 0, 0};
      for (int32_t i = rings.offsets[v]; i < rings.offsets[v + 1]; ++i)
        mean = mean + at(dir, rings.ids[size_t(i)]);
      const Vec3 d = normalized(at(dir, int32_t(v)) + normalized(mean));
      if (norm(d) > 0.5) put(next, int32_t(v), d);
    }
    dir.swap(next);
    next = dir;
  }

  // Phase 4: plane guard near the openings.
  if (!reach.empty()) {
    std::vector<double> rim_radius(openings.size(), 0.0);
    for (size_t o = 0; o < openings.size(); ++o)
      for (int32_t v : openings[o].rim)
        rim_radius[o] = std::max(rim_radius[o], norm(at(wall.points, v) - openings[o].origin));
    for (size_t v = 0; v < nv; ++v) {
      if (out.opening_of[v] >= 0) continue;
      const Vec3 p = at(wall.points, int32_t(v));
      for (size_t o = 0; o < openings.size(); ++o) {
        const LayerOpening& op = openings[o];
        if (norm(p - op.origin) > rim_radius[o] + 2 * reach[v]) continue;
        const double s = dot(p - op.origin, op.normal);  // < 0 on the lumen side
        if (!(s < 0)) continue;
        const Vec3 d = at(dir, int32_t(v));
        const Vec3 end = p + reach[v] * d;
        const double s_end = dot(end - op.origin, op.normal);
        if (s_end <= 0.5 * s) continue;
        // Only where the column ends over the cap or its ring, not where it
        // merely approaches the plane's extension beside the opening.
        if (norm(end - s_end * op.normal - op.origin) > rim_radius[o] + reach[v]) continue;
        const double allowed = std::min(1.0, -s / (2 * reach[v]));
        const Vec3 across = normalized(d - dot(d, op.normal) * op.normal);
        if (!(norm(across) > 0.5)) continue;  // along the normal: left to validation
        put(dir, int32_t(v), std::sqrt(1 - allowed * allowed) * across + allowed * op.normal);
      }
    }
  }

  // Phase 5: visibility of the star's triangles.
  out.min_visibility = 1;
  for (size_t v = 0; v < nv; ++v) {
    const int32_t o = out.opening_of[v];
    const LayerOpening* plane = o >= 0 ? &openings[size_t(o)] : nullptr;
    auto [d, w] = make_visible(adj, out.triangle_normal, v, at(dir, int32_t(v)), plane);
    if (w < kVisibilityTarget && !plane) {
      // The plain normal may see the star better than the smoothed one.
      auto [d2, w2] = make_visible(adj, out.triangle_normal, v, at(out.normal, int32_t(v)), plane);
      if (w2 > w) d = d2, w = w2;
    }
    if (!(w >= kVisibilityFloor))
      return Status::Error(std::string("no ") + (outward ? "outward" : "inward") +
                           " direction sees all the triangles around wall vertex " +
                           std::to_string(v) + " " + where(wall, v) +
                           (plane ? " from within its cap plane (the wall meets the plane at a "
                                    "grazing angle there)"
                                  : " (a needle-like spike or fold of the wall)"))
          // At a rim, the opening is better cut deeper, where the wall
          // crosses its plane; elsewhere, no layer can start there.
          .WithRemedy({plane ? "trim_end" : "no_layers", {at(wall.points, int32_t(v))}, 0});
    put(dir, int32_t(v), d);
    out.min_visibility = std::min(out.min_visibility, w);
  }
  return out;
}

}  // namespace vm
