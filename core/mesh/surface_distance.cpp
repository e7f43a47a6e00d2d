// Branch-and-bound closest-point search in a box hierarchy (Ericson,
// "Real-Time Collision Detection", 2005, section 6.3): visit the nearer child
// box first, prune any box farther than the best distance so far; exact point
// to triangle distance from geom/closest_point.h.
#include "core/mesh/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/geom/closest_point.h"
#include "core/util/parallel.h"

namespace vm {
namespace {

// Squared distance from q to the box [lo, hi].
double box_distance2(const double* q, const double* lo, const double* hi) {
  double s = 0;
  for (int d = 0; d < 3; ++d) {
    const double e = q[d] < lo[d] ? lo[d] - q[d] : q[d] > hi[d] ? q[d] - hi[d] : 0.0;
    s += e * e;
  }
  return s;
}

}  // namespace

SurfacePoint closest_surface_point(const SurfaceMesh& surface, const TriangleBvh& bvh,
                                   const double* q) {
  SurfacePoint best;
  best.distance = std::numeric_limits<double>::infinity();
  if (bvh.empty()) return best;
  double best2 = std::numeric_limits<double>::infinity();
  // Depth-first, nearer child on top of the stack; each entry carries its
  // box distance so it can be pruned when popped.
  struct Entry {
    int32_t node;
    double d2;
  };
  Entry stack[128];
  int top = 0;
  stack[top++] = {0, box_distance2(q, bvh.nodes[0].lo, bvh.nodes[0].hi)};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.d2 >= best2) continue;
    const TriangleBvh::Node& n = bvh.nodes[size_t(e.node)];
    if (TriangleBvh::is_leaf(n)) {
      for (int32_t i = n.first; i < n.first + n.count; ++i) {
        const int32_t t = bvh.order[size_t(i)];
        const int32_t* v = &surface.triangles[3 * size_t(t)];
        double c[3];
        const double d2 = closest_point_on_triangle(q, &surface.points[3 * size_t(v[0])],
                                                    &surface.points[3 * size_t(v[1])],
                                                    &surface.points[3 * size_t(v[2])], c);
        if (d2 < best2) {
          best2 = d2;
          best.triangle = t;
          best.point = {c[0], c[1], c[2]};
        }
      }
      continue;
    }
    const TriangleBvh::Node& l = bvh.nodes[size_t(n.first)];
    const TriangleBvh::Node& r = bvh.nodes[size_t(n.first) + 1];
    Entry a{n.first, box_distance2(q, l.lo, l.hi)}, b{n.first + 1, box_distance2(q, r.lo, r.hi)};
    if (a.d2 < b.d2) std::swap(a, b);  // push the farther first, pop the nearer first
    // Median splits keep the depth near log2(n / leaf); 128 entries cover
    // any tree the build makes (the stack holds at most one entry per level
    // plus one).
    if (a.d2 < best2 && top < 127) stack[top++] = a;
    if (b.d2 < best2 && top < 127) stack[top++] = b;
  }
  best.distance = std::sqrt(best2);
  return best;
}

DistanceReport distances_to_surface(const SurfaceMesh& surface, const std::vector<double>& points,
                                    bool keep_per_point) {
  if (points.empty()) return distances_to_surface(surface, TriangleBvh{}, points, keep_per_point);
  return distances_to_surface(surface, build_triangle_bvh(surface), points, keep_per_point);
}

DistanceReport distances_to_surface(const SurfaceMesh& surface, const TriangleBvh& bvh,
                                    const std::vector<double>& points, bool keep_per_point) {
  DistanceReport r;
  r.count = points.size() / 3;
  if (keep_per_point) r.per_point.resize(r.count);
  if (r.count == 0) return r;
  // The queries on the threads, each distance into its slot; the summary in
  // point order, so it does not depend on the thread count.
  std::vector<double> local;
  std::vector<double>& d = keep_per_point ? r.per_point : local;
  d.resize(r.count);
  parallel_for(r.count, 1024, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i)
      d[i] = closest_surface_point(surface, bvh, &points[3 * i]).distance;
  });
  double sum = 0;
  for (size_t i = 0; i < r.count; ++i) {
    sum += d[i];
    if (d[i] > r.max || i == 0) {
      r.max = d[i];
      r.argmax = i;
    }
  }
  r.mean = sum / double(r.count);
  return r;
}

}  // namespace vm
