// Places where a surface crosses itself (see the header): the exact pairs
// of mesh/self_intersection, grouped with a union-find, each place located
// by a crossing point of one of its pairs.
#include "core/mesh/self_crossings.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>

#include "core/mesh/self_intersection.h"

namespace vm {
namespace {

using Corners = std::array<Vec3, 3>;

Corners corners(const SurfaceMesh& mesh, int32_t t) {
  const int32_t* c = &mesh.triangles[3 * size_t(t)];
  return {at(mesh.points, c[0]), at(mesh.points, c[1]), at(mesh.points, c[2])};
}

/// Adds to `sum` (and counts in `n`) the points where edges of triangle `a`
/// pass through the plane of triangle `b` inside it (a small tolerance keeps
/// points on b's edges, where rounding may put them just outside).
void add_piercings(const Corners& a, const Corners& b, Vec3& sum, int& n) {
  const Vec3 normal = cross(b[1] - b[0], b[2] - b[0]);
  const double tolerance = 1e-9 * dot(normal, normal);
  for (int k = 0; k < 3; ++k) {
    const Vec3& p = a[size_t(k)];
    const Vec3& q = a[size_t((k + 1) % 3)];
    const double dp = dot(normal, p - b[0]), dq = dot(normal, q - b[0]);
    if ((dp > 0 && dq > 0) || (dp < 0 && dq < 0) || dp == dq) continue;
    const Vec3 x = p + (dp / (dp - dq)) * (q - p);
    bool inside = true;
    for (int e = 0; e < 3 && inside; ++e) {
      const Vec3& u = b[size_t(e)];
      const Vec3& v = b[size_t((e + 1) % 3)];
      inside = dot(cross(v - u, x - u), normal) >= -tolerance;
    }
    if (inside) sum = sum + x, ++n;
  }
}

/// The mean of the ends of the intersection segment of triangles s and t
/// (the points where an edge of one passes through the other); for a
/// coplanar overlap, the mean of their six corners.
Vec3 crossing_point(const SurfaceMesh& mesh, int32_t s, int32_t t) {
  const Corners a = corners(mesh, s), b = corners(mesh, t);
  Vec3 sum{0, 0, 0};
  int n = 0;
  add_piercings(a, b, sum, n);
  add_piercings(b, a, sum, n);
  if (n == 0) {
    for (int k = 0; k < 3; ++k) sum = sum + a[size_t(k)] + b[size_t(k)];
    n = 6;
  }
  return (1.0 / n) * sum;
}

/// Union-find over the crossing triangles (dense indices).
struct Groups {
  std::vector<int32_t> parent;
  int32_t find(int32_t x) {
    while (parent[size_t(x)] != x) x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
    return x;
  }
  void join(int32_t a, int32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[size_t(std::max(a, b))] = std::min(a, b);
  }
};

}  // namespace

SelfCrossings find_self_crossings(const SurfaceMesh& mesh, size_t max_places, size_t max_pairs) {
  SelfCrossings out;
  const SelfIntersectionReport report = find_self_intersections(mesh, max_pairs);
  out.pairs = report.pairs;
  if (report.examples.empty()) return out;

  // Phase 1: the crossing triangles, numbered densely, grouped by their
  // pairs and by shared vertices.
  std::vector<int32_t> dense(mesh.num_triangles(), -1);
  std::vector<int32_t> triangle_of;  // dense -> triangle
  for (const auto& pair : report.examples)
    for (int32_t t : pair)
      if (dense[size_t(t)] < 0) {
        dense[size_t(t)] = int32_t(triangle_of.size());
        triangle_of.push_back(t);
      }
  Groups groups;
  groups.parent.resize(triangle_of.size());
  std::iota(groups.parent.begin(), groups.parent.end(), 0);
  for (const auto& pair : report.examples)
    groups.join(dense[size_t(pair[0])], dense[size_t(pair[1])]);
  std::vector<int32_t> first_at_vertex(mesh.num_vertices(), -1);
  for (size_t d = 0; d < triangle_of.size(); ++d)
    for (int k = 0; k < 3; ++k) {
      int32_t& first =
          first_at_vertex[size_t(mesh.triangles[3 * size_t(triangle_of[d]) + size_t(k)])];
      if (first < 0)
        first = int32_t(d);
      else
        groups.join(first, int32_t(d));
    }

  // Phase 2: per place, its pairs' crossing points; the place's point is
  // the crossing point nearest their mean.
  struct Place {
    size_t pairs = 0;
    Vec3 sum{0, 0, 0};
    Vec3 point{0, 0, 0};
    double best = -1;
  };
  std::vector<int32_t> place_of_root(triangle_of.size(), -1);
  std::vector<Place> places;
  std::vector<Vec3> points(report.examples.size());
  std::vector<int32_t> place_of_pair(report.examples.size());
  for (size_t i = 0; i < report.examples.size(); ++i) {
    const auto& pair = report.examples[i];
    const int32_t root = groups.find(dense[size_t(pair[0])]);
    if (place_of_root[size_t(root)] < 0) {
      place_of_root[size_t(root)] = int32_t(places.size());
      places.emplace_back();
    }
    Place& p = places[size_t(place_of_root[size_t(root)])];
    points[i] = crossing_point(mesh, pair[0], pair[1]);
    place_of_pair[i] = place_of_root[size_t(root)];
    p.sum = p.sum + points[i];
    ++p.pairs;
  }
  for (size_t i = 0; i < points.size(); ++i) {
    Place& p = places[size_t(place_of_pair[i])];
    const Vec3 d = points[i] - (1.0 / double(p.pairs)) * p.sum;
    if (p.best < 0 || dot(d, d) < p.best) p.best = dot(d, d), p.point = points[i];
  }
  std::stable_sort(places.begin(), places.end(),
                   [](const Place& a, const Place& b) { return a.pairs > b.pairs; });
  out.place_count = places.size();
  for (size_t i = 0; i < places.size() && i < max_places; ++i)
    out.places.push_back(places[i].point);
  return out;
}

}  // namespace vm
