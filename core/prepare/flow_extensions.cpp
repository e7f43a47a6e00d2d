// Flow extensions at the openings (flow_extensions.h), in phases: (1) per
// opening, the rim's directions into the extension (the wall's own, from
// each rim vertex's inner neighbours, so the join is smooth) and the end
// circle; (2) rings of vertices along a Hermite curve from each rim vertex
// to its circle point (halfway, at most 2.5 radii out), then straight to
// the end; (3) bands of triangles between consecutive rings, oriented like
// the wall; (4) a check that no new triangle crosses the surface.
#include "core/prepare/flow_extensions.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/self_intersection.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

Vec3 at(const SurfaceMesh& m, int32_t v) { return vm::at(m.points, v); }
Vec3 add(const Vec3& a, const Vec3& b, double s = 1) { return a + s * b; }
Vec3 unit(const Vec3& a) {
  const double n = norm(a);
  return n > 0 ? Vec3{a[0] / n, a[1] / n, a[2] / n} : Vec3{0, 0, 0};
}

/// Hermite curve from p0 (tangent t0) to p1 (tangent t1) at s in [0, 1].
Vec3 hermite(const Vec3& p0, const Vec3& t0, const Vec3& p1, const Vec3& t1, double s) {
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2,
               h11 = s3 - s2;
  Vec3 p;
  for (size_t k = 0; k < 3; ++k) p[k] = h00 * p0[k] + h10 * t0[k] + h01 * p1[k] + h11 * t1[k];
  return p;
}

/// Phase 1 for one opening: the direction into the extension at each rim
/// vertex, the wall's own direction there: in each wall triangle at a rim
/// edge, the direction perpendicular to that edge, away from the triangle
/// (exact for a cylinder cut straight); a vertex takes the mean of its two
/// rim edges', turned toward the normal where it points back.
std::vector<Vec3> rim_directions(const SurfaceMesh& m, const TriangleAdjacency& stars,
                                 const std::vector<int32_t>& loop, const Vec3& normal) {
  const size_t n = loop.size();
  std::vector<Vec3> edge_dir(n);
  for (size_t i = 0; i < n; ++i) {
    const int32_t a = loop[i], b = loop[(i + 1) % n];
    edge_dir[i] = normal;
    for (int32_t s = stars.star_offsets[size_t(a)]; s < stars.star_offsets[size_t(a) + 1]; ++s) {
      const int32_t* t = &m.triangles[3 * size_t(stars.star[size_t(s)])];
      if (t[0] != b && t[1] != b && t[2] != b) continue;
      const int32_t o = t[0] != a && t[0] != b ? t[0] : t[1] != a && t[1] != b ? t[1] : t[2];
      const Vec3 pa = at(m, a), edge = (at(m, b) - pa), inward = (at(m, o) - pa);
      Vec3 d = cross(edge, cross(edge, inward));
      if (dot(d, inward) > 0)
        for (double& x : d) x = -x;
      if (norm(d) > 0) edge_dir[i] = unit(d);
    }
  }
  std::vector<Vec3> dirs(n);
  for (size_t i = 0; i < n; ++i) {
    Vec3 d = unit(add(edge_dir[(i + n - 1) % n], edge_dir[i]));
    if (norm(d) == 0) d = normal;
    // A wall that leaves the rim backwards or sideways would fold the
    // extension: keep the direction within 60 degrees of the normal.
    for (int k = 0; k < 8 && dot(d, normal) < 0.5; ++k) d = unit(add(d, normal));
    dirs[i] = d;
  }
  return dirs;
}

// Length of the join from the rim's shape to the circle, in the opening's
// radii (the first half of a 5-radius extension).
constexpr double kBlendRadii = 2.5;

}  // namespace

Result<std::vector<FlowExtension>> add_flow_extensions(SurfaceMesh& mesh,
                                                       std::vector<int32_t>* labels,
                                                       const std::vector<Opening>& openings,
                                                       const std::vector<double>& lengths,
                                                       std::vector<int32_t>* new_vertex_opening) {
  using R = Result<std::vector<FlowExtension>>;
  std::vector<FlowExtension> out;
  if (labels && labels->size() != mesh.num_triangles()) labels = nullptr;
  const size_t first_new_triangle = mesh.num_triangles();
  const TriangleAdjacency stars = build_adjacency(mesh);
  for (size_t o = 0; o < openings.size() && o < lengths.size(); ++o) {
    if (!(lengths[o] > 0)) continue;
    const Opening& op = openings[o];
    const std::vector<int32_t>& loop = op.loop;
    const size_t n = loop.size();
    const Vec3 c = op.centroid, axis = op.normal;
    const double height = lengths[o] * op.radius;
    // A polygon of n points on a circle of this radius has the opening's
    // area, so the opening keeps its equivalent radius (and its place in
    // the analysis' order).
    const double angle = 2 * std::numbers::pi / double(n);
    const double radius = op.radius * std::sqrt(angle / pm::sin(angle));
    // Phase 1: directions and the end circle's points.
    std::vector<Vec3> dirs = rim_directions(mesh, stars, loop, axis);
    std::vector<Vec3> rim(n), ring_dir(n);
    double edge = 0;
    for (size_t i = 0; i < n; ++i) {
      rim[i] = at(mesh, loop[i]);
      edge += norm(at(mesh, loop[(i + 1) % n]) - rim[i]) / double(n);
      const Vec3 r = (rim[i] - c);
      const Vec3 in_plane = add(r, axis, -dot(r, axis));
      if (norm(in_plane) < 1e-6 * op.radius)
        return R::Error("opening " + std::to_string(o + 1) + " at " + point_text(c) +
                        " folds back onto its axis: it cannot be extended; extend it less "
                        "({flow_extension} " +
                        std::to_string(o + 1) + "=0)");
      ring_dir[i] = unit(in_plane);
    }
    // The end is a regular polygon (so it has the opening's area and
    // centroid exactly), its corners at equal angles turned to follow the
    // rim's as closely as possible (the circular mean of the differences).
    const Vec3 e1 = ring_dir[0], e2 = cross(axis, e1);
    std::vector<double> phi(n);
    for (size_t i = 0; i < n; ++i) phi[i] = pm::atan2(dot(ring_dir[i], e2), dot(ring_dir[i], e1));
    // The loop's sense of rotation about the axis (clockwise for an
    // outward surface's boundary, as the normal is against its area).
    double winding = 0;
    for (size_t i = 0; i < n; ++i) winding += pm::sin(phi[(i + 1) % n] - phi[i]);
    const double step = winding < 0 ? -angle : angle;
    double sum_cos = 0, sum_sin = 0;
    for (size_t i = 0; i < n; ++i) {
      sum_cos += pm::cos(phi[i] - step * double(i));
      sum_sin += pm::sin(phi[i] - step * double(i));
    }
    const double turn = pm::atan2(sum_sin, sum_cos);
    for (size_t i = 0; i < n; ++i) {
      const double theta = turn + step * double(i);
      ring_dir[i] =
          add(Vec3{e1[0] * pm::cos(theta), e1[1] * pm::cos(theta), e1[2] * pm::cos(theta)}, e2,
              pm::sin(theta));
      // The join leaves the rim in the wall's meridian plane (axis, radial
      // direction): a circumferential component would twist the extension.
      const Vec3 around = cross(axis, unit(rim[i] - add(c, axis, dot(rim[i] - c, axis))));
      dirs[i] = unit(add(dirs[i], around, -dot(dirs[i], around)));
    }
    // Phase 2: rings. The cross-section blends over the first half of the
    // extension, at most kBlendRadii radii (Hermite, leaving the rim in the
    // wall's direction, arriving along the axis), then runs straight. The
    // Hermite tangents scale with the blend's chord: a blend as long as
    // half of a long extension would swing out by radii and pinch the tube.
    const size_t rings = std::max<size_t>(2, size_t(std::ceil(height / std::max(edge, 1e-300))));
    const double half = std::min(0.5 * height, kBlendRadii * op.radius);
    std::vector<int32_t> previous(loop.begin(), loop.end()), current(n);
    for (size_t j = 1; j <= rings; ++j) {
      const double z = height * double(j) / double(rings);
      for (size_t i = 0; i < n; ++i) {
        const Vec3 mid = add(add(c, axis, half), ring_dir[i], radius);
        Vec3 p;
        if (z <= half) {
          const double chord = norm((mid - rim[i]));
          Vec3 t0 = dirs[i], t1 = axis;
          for (double& x : t0) x *= chord;
          for (double& x : t1) x *= chord;
          p = hermite(rim[i], t0, mid, t1, z / half);
        } else {
          p = add(mid, axis, z - half);
        }
        current[i] = int32_t(mesh.num_vertices());
        mesh.points.insert(mesh.points.end(), p.begin(), p.end());
        if (new_vertex_opening) new_vertex_opening->push_back(int32_t(o));
      }
      // Phase 3: the band, traversing each rim edge against the wall's
      // half-edge (loop order), so orientation carries over.
      for (size_t i = 0; i < n; ++i) {
        const size_t k = (i + 1) % n;
        mesh.triangles.insert(mesh.triangles.end(), {previous[k], previous[i], current[i]});
        mesh.triangles.insert(mesh.triangles.end(), {previous[k], current[i], current[k]});
      }
      if (labels) {
        // The label of the wall triangle at each rim edge.
        for (size_t i = 0; i < n; ++i) {
          int32_t label = labels->empty() ? 0 : (*labels)[0];
          const int32_t a = loop[i], b = loop[(i + 1) % n];
          for (int32_t s = stars.star_offsets[size_t(a)]; s < stars.star_offsets[size_t(a) + 1];
               ++s) {
            const int32_t t = stars.star[size_t(s)];
            const int32_t* tri = &mesh.triangles[3 * size_t(t)];
            if (tri[0] == b || tri[1] == b || tri[2] == b) label = (*labels)[size_t(t)];
          }
          labels->insert(labels->end(), {label, label});
        }
      }
      previous = current;
    }
    FlowExtension fe;
    fe.opening = o;
    fe.length = height;
    fe.rings = rings;
    fe.end = add(c, axis, height);
    out.push_back(fe);
  }
  // Phase 4: no new triangle may cross the surface.
  if (mesh.num_triangles() > first_new_triangle) {
    std::vector<uint8_t> flagged(mesh.num_triangles(), 0);
    std::fill(flagged.begin() + long(first_new_triangle), flagged.end(), uint8_t(1));
    const SelfIntersectionReport crossing = find_self_intersections_of(mesh, flagged, 1);
    if (crossing.pairs > 0) {
      const int32_t t = std::max(crossing.examples[0][0], crossing.examples[0][1]);
      const Vec3 p = at(mesh, mesh.triangles[3 * size_t(t)]);
      return R::Error("a flow extension runs into the surface near " + point_text(p) +
                      ": make it shorter ({flow_extension} K=L for that opening) or cut the "
                      "vessel end first");
    }
  }
  return out;
}

}  // namespace vm
