// Half-chord radius (see chord_radius.h): angle-weighted normals, rays
// through a bounding-volume hierarchy (mesh/triangle_bvh.h) with slab tests
// and the Moller-Trumbore ray-triangle test (Moller and Trumbore, "Fast,
// minimum storage ray-triangle intersection", JGT 2, 1997), 1-ring medians.
#include "core/mesh/chord_radius.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/geom/vec3.h"
#include "core/mesh/triangle_bvh.h"
#include "core/util/parallel.h"
#include "core/util/portable_math.h"

namespace vm {

namespace {

// Distance along the unit ray o + s d (s > s_min) to triangle t, or +inf.
double ray_triangle(const SurfaceMesh& m, int32_t t, const Vec3& o, const Vec3& d, double s_min) {
  const int32_t* f = &m.triangles[3 * size_t(t)];
  const Vec3 a = at(m.points, f[0]), b = at(m.points, f[1]), c = at(m.points, f[2]);
  const Vec3 e1 = b - a, e2 = c - a, p = cross(d, e2);
  const double det = dot(e1, p);
  if (det == 0) return std::numeric_limits<double>::infinity();
  const double inv = 1 / det;
  const Vec3 q = o - a;
  const double u = dot(q, p) * inv;
  if (u < 0 || u > 1) return std::numeric_limits<double>::infinity();
  const Vec3 r = cross(q, e1);
  const double v = dot(d, r) * inv;
  if (v < 0 || u + v > 1) return std::numeric_limits<double>::infinity();
  const double s = dot(e2, r) * inv;
  return s > s_min ? s : std::numeric_limits<double>::infinity();
}

}  // namespace

std::vector<double> half_chords(const SurfaceMesh& wall, const std::vector<int32_t>& vertices) {
  const size_t nv = wall.num_vertices(), nt = wall.num_triangles();
  std::vector<double> normal(3 * nv, 0.0);
  for (size_t t = 0; t < nt; ++t) {
    const int32_t* v = &wall.triangles[3 * t];
    const Vec3 p[3] = {at(wall.points, v[0]), at(wall.points, v[1]), at(wall.points, v[2])};
    const Vec3 n = normalized(cross(p[1] - p[0], p[2] - p[0]));
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = normalized(p[(k + 1) % 3] - p[k]), b = normalized(p[(k + 2) % 3] - p[k]);
      const double angle = pm::acos(std::clamp(dot(a, b), -1.0, 1.0));
      for (int d = 0; d < 3; ++d) normal[3 * size_t(v[k]) + size_t(d)] -= angle * n[d];
    }
  }
  const double diag = bounding_box(wall.points).diagonal();
  const double s_min = 1e-9 * diag;
  const TriangleBvh bvh = build_triangle_bvh(wall, 4);
  std::vector<double> radius(vertices.size(), -1.0);
  if (bvh.empty()) return radius;
  // Each vertex's ray on the threads, into its slot.
  parallel_for(vertices.size(), 1024, [&](size_t first, size_t last) {
    std::vector<int32_t> stack;
    for (size_t i = first; i < last; ++i) {
      const int32_t v = vertices[i];
      const Vec3 o = at(wall.points, v);
      const Vec3 d = normalized(at(normal, v));
      if (!(norm(d) > 0.5)) continue;
      const double inv[3] = {1 / d[0], 1 / d[1], 1 / d[2]};
      double best = std::numeric_limits<double>::infinity();
      stack.assign(1, 0);
      while (!stack.empty()) {
        const TriangleBvh::Node& n = bvh.nodes[size_t(stack.back())];
        stack.pop_back();
        // Slab test of the box against the ray segment [0, best].
        double lo = 0, hi = best;
        for (int k = 0; k < 3 && lo <= hi; ++k) {
          double s0 = (n.lo[k] - o[k]) * inv[k], s1 = (n.hi[k] - o[k]) * inv[k];
          if (std::isnan(s0) || std::isnan(s1)) {  // d[k] == 0 and o on a slab plane
            if (o[k] < n.lo[k] || o[k] > n.hi[k]) hi = -1;
            continue;
          }
          if (s0 > s1) std::swap(s0, s1);
          lo = std::max(lo, s0);
          hi = std::min(hi, s1);
        }
        if (lo > hi) continue;
        if (!TriangleBvh::is_leaf(n)) {
          stack.push_back(n.first);
          stack.push_back(n.first + 1);
          continue;
        }
        for (int32_t j = n.first; j < n.first + n.count; ++j) {
          const int32_t t = bvh.order[size_t(j)];
          const int32_t* f = &wall.triangles[3 * size_t(t)];
          if (f[0] == v || f[1] == v || f[2] == v) continue;
          best = std::min(best, ray_triangle(wall, t, o, d, s_min));
        }
      }
      if (std::isfinite(best)) radius[i] = 0.5 * best;
    }
  });
  return radius;
}

std::vector<double> chord_radius(const SurfaceMesh& wall) {
  const size_t nv = wall.num_vertices(), nt = wall.num_triangles();
  const double diag = bounding_box(wall.points).diagonal();
  std::vector<int32_t> all(nv);
  for (size_t v = 0; v < nv; ++v) all[v] = int32_t(v);
  std::vector<double> radius = half_chords(wall, all);
  // Rays that left through an opening: their neighbors' median, grown in
  // from the measured vertices; then two passes of a 1-ring median.
  std::vector<std::vector<int32_t>> ring(nv);
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = wall.triangles[3 * t + size_t(k)];
      const int32_t b = wall.triangles[3 * t + size_t(k + 1) % 3];
      ring[size_t(a)].push_back(b);
      ring[size_t(b)].push_back(a);
    }
  std::vector<double> next(nv), values;
  auto median_of = [&](size_t v, bool self) {
    values.clear();
    if (self && radius[v] > 0) values.push_back(radius[v]);
    for (int32_t u : ring[v])
      if (radius[size_t(u)] > 0) values.push_back(radius[size_t(u)]);
    if (values.empty()) return -1.0;
    std::nth_element(values.begin(), values.begin() + long(values.size() / 2), values.end());
    return values[values.size() / 2];
  };
  for (bool missing = true; missing;) {
    missing = false;
    bool progress = false;
    next = radius;
    for (size_t v = 0; v < nv; ++v)
      if (!(radius[v] > 0)) {
        next[v] = median_of(v, false);
        (next[v] > 0 ? progress : missing) = true;
      }
    radius.swap(next);
    if (!progress) break;
  }
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t v = 0; v < nv; ++v) next[v] = median_of(v, true);
    radius.swap(next);
  }
  for (double& r : radius)
    if (!(r > 0)) r = 0.5 * diag;  // no ray met the wall at all
  return radius;
}

}  // namespace vm
