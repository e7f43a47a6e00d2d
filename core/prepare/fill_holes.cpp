// Hole filling after Liepa, "Filling holes in meshes" (SGP 2003): an
// initial triangulation of the loop (here ear clipping in the loop's plane,
// each step taking the ear of largest smallest angle), refinement by
// centroid splits where a triangle is larger than the rim's edge length,
// Delaunay edge flips, and umbrella smoothing of the new vertices.
#include "core/prepare/fill_holes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <utility>

#include "core/geom/vec3.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

using Edge = std::pair<int32_t, int32_t>;
Edge key(int32_t a, int32_t b) { return {std::min(a, b), std::max(a, b)}; }

/// Smallest angle of triangle (a, b, c), radians.
double min_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  auto angle = [](const Vec3& p, const Vec3& q, const Vec3& r) {
    const Vec3 u = q - p, v = r - p;
    return pm::atan2(norm(cross(u, v)), dot(u, v));
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
}

/// Angle at p of triangle (p, q, r), radians.
double angle_at(const Vec3& p, const Vec3& q, const Vec3& r) {
  const Vec3 u = q - p, v = r - p;
  return pm::atan2(norm(cross(u, v)), dot(u, v));
}

struct Patch {
  SurfaceMesh& mesh;
  std::vector<std::array<int32_t, 3>> tris;
  const std::set<Edge>& existing;  ///< the surface's edges between loop vertices
  Vec3 normal;                     ///< the loop's unit vector area (fill side)

  Vec3 p(int32_t v) const { return at(mesh.points, v); }
  Vec3 tri_normal(const std::array<int32_t, 3>& t) const {
    return cross(p(t[1]) - p(t[0]), p(t[2]) - p(t[0]));
  }

  /// Flips interior edges that fail the Delaunay test (opposite angles
  /// summing to more than pi) when the flip keeps both triangles facing
  /// the loop's way and makes no edge the surface already has.
  void flip_to_delaunay() {
    for (int sweep = 0; sweep < 50; ++sweep) {
      std::map<Edge, std::vector<std::pair<size_t, int>>> edges;
      for (size_t t = 0; t < tris.size(); ++t)
        for (int k = 0; k < 3; ++k)
          edges[key(tris[t][size_t(k)], tris[t][size_t(k + 1) % 3])].push_back({t, k});
      bool flipped = false;
      std::vector<uint8_t> touched(tris.size(), 0);
      for (const auto& [e, uses] : edges) {
        if (uses.size() != 2) continue;
        const auto [t1, k1] = uses[0];
        const auto [t2, k2] = uses[1];
        if (touched[t1] || touched[t2]) continue;
        const int32_t a = tris[t1][size_t(k1)], b = tris[t1][size_t(k1 + 1) % 3];
        const int32_t c = tris[t1][size_t(k1 + 2) % 3], d = tris[t2][size_t(k2 + 2) % 3];
        if (angle_at(p(c), p(a), p(b)) + angle_at(p(d), p(a), p(b)) <= std::numbers::pi + 1e-9)
          continue;
        if (existing.count(key(c, d)) || edges.count(key(c, d))) continue;
        const std::array<int32_t, 3> n1{c, a, d}, n2{d, b, c};
        if (dot(tri_normal(n1), normal) <= 0 || dot(tri_normal(n2), normal) <= 0) continue;
        tris[t1] = n1;
        tris[t2] = n2;
        touched[t1] = touched[t2] = 1;
        flipped = true;
      }
      if (!flipped) return;
    }
  }
};

/// Ear clipping of polygon `poly` (counter-clockwise seen along `normal`)
/// in the plane; empty if no triangulation avoids the existing edges.
std::vector<std::array<int32_t, 3>> ear_clip(const SurfaceMesh& mesh, std::vector<int32_t> poly,
                                             const Vec3& normal, const std::set<Edge>& existing) {
  const Vec3 e1 =
      normalized(cross(normal, std::abs(normal[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
  const Vec3 e2 = cross(normal, e1);
  auto uv = [&](int32_t v) {
    const Vec3 q = at(mesh.points, v);
    return std::array<double, 2>{dot(q, e1), dot(q, e2)};
  };
  auto orient = [](const std::array<double, 2>& a, const std::array<double, 2>& b,
                   const std::array<double, 2>& c) {
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
  };
  std::vector<std::array<int32_t, 3>> out;
  std::set<Edge> made;
  while (poly.size() > 3) {
    const size_t n = poly.size();
    // Best ear: convex, empty, a new diagonal; then relax emptiness, then
    // convexity, so that some ear is always taken.
    long best = -1;
    int best_level = 3;
    double best_q = -1;
    for (size_t i = 0; i < n; ++i) {
      const int32_t a = poly[(i + n - 1) % n], b = poly[i], c = poly[(i + 1) % n];
      if (existing.count(key(a, c)) || made.count(key(a, c))) continue;
      const auto pa = uv(a), pb = uv(b), pc = uv(c);
      const bool convex = orient(pa, pb, pc) > 0;
      bool empty = true;
      for (size_t j = 0; j < n && empty && convex; ++j) {
        const int32_t v = poly[j];
        if (v == a || v == b || v == c) continue;
        const auto q = uv(v);
        empty = !(orient(pa, pb, q) >= 0 && orient(pb, pc, q) >= 0 && orient(pc, pa, q) >= 0);
      }
      const int level = convex && empty ? 0 : convex ? 1 : 2;
      const double quality = min_angle(at(mesh.points, a), at(mesh.points, b), at(mesh.points, c));
      if (level < best_level || (level == best_level && quality > best_q))
        best = long(i), best_level = level, best_q = quality;
    }
    if (best < 0) return {};
    const size_t i = size_t(best);
    const int32_t a = poly[(i + n - 1) % n], b = poly[i], c = poly[(i + 1) % n];
    out.push_back({a, b, c});
    made.insert(key(a, c));
    poly.erase(poly.begin() + long(i));
  }
  if (poly.size() == 3) out.push_back({poly[0], poly[1], poly[2]});
  return out;
}

}  // namespace

std::vector<HoleFill> fill_holes(SurfaceMesh& mesh, const std::vector<std::vector<int32_t>>& loops,
                                 std::vector<int32_t>* labels) {
  if (labels && labels->size() != mesh.num_triangles()) labels = nullptr;
  std::vector<HoleFill> result(loops.size());
  // The surface's edges between loop vertices (a fill must not repeat
  // them) and the triangle on each directed edge, for the labels.
  std::vector<uint8_t> on_loop(mesh.num_vertices(), 0);
  for (const auto& loop : loops)
    for (int32_t v : loop) on_loop[size_t(v)] = 1;
  std::set<Edge> existing;
  std::map<Edge, int32_t> triangle_on;
  const size_t nt = mesh.num_triangles();
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = mesh.triangles[3 * t + size_t(k)];
      const int32_t b = mesh.triangles[3 * t + size_t(k + 1) % 3];
      if (!on_loop[size_t(a)] || !on_loop[size_t(b)]) continue;
      existing.insert(key(a, b));
      triangle_on[{a, b}] = int32_t(t);
    }
  for (size_t l = 0; l < loops.size(); ++l) {
    const auto& loop = loops[l];
    const size_t n = loop.size();
    if (n < 3) continue;
    // The fill runs against the loop, so its edges oppose the boundary's.
    std::vector<int32_t> poly(loop.rbegin(), loop.rend());
    Vec3 normal{};
    double rim = 0;
    for (size_t i = 0; i < n; ++i) {
      const Vec3 p = at(mesh.points, poly[i]), q = at(mesh.points, poly[(i + 1) % n]);
      normal = normal + cross(p, q);
      rim += norm(q - p) / double(n);
    }
    normal = normalized(normal);
    if (!(norm(normal) > 0) || !(rim > 0)) continue;
    Patch patch{mesh, ear_clip(mesh, poly, normal, existing), existing, normal};
    if (patch.tris.empty()) continue;
    // Liepa's refinement with a constant scale (the rim's mean edge): a
    // triangle is split at its centroid while the centroid is farther than
    // scale / sqrt(2) from all three corners.
    const size_t first_new = mesh.num_vertices();
    patch.flip_to_delaunay();
    for (int round = 0; round < 10; ++round) {
      bool split = false;
      const size_t count = patch.tris.size();
      for (size_t t = 0; t < count; ++t) {
        const auto tri = patch.tris[t];
        const Vec3 c = (1.0 / 3) * (patch.p(tri[0]) + patch.p(tri[1]) + patch.p(tri[2]));
        bool big = true;
        for (int32_t v : tri) big = big && std::sqrt(2.0) * norm(c - patch.p(v)) > rim;
        if (!big) continue;
        const int32_t m = int32_t(mesh.num_vertices());
        mesh.points.insert(mesh.points.end(), c.begin(), c.end());
        patch.tris[t] = {tri[0], tri[1], m};
        patch.tris.push_back({tri[1], tri[2], m});
        patch.tris.push_back({tri[2], tri[0], m});
        split = true;
      }
      patch.flip_to_delaunay();
      if (!split) break;
    }
    // Umbrella smoothing of the new vertices (the rim stays).
    const size_t added = mesh.num_vertices() - first_new;
    for (int pass = 0; pass < 3 && added > 0; ++pass) {
      std::vector<Vec3> sum(added, Vec3{});
      std::vector<int> count(added, 0);
      for (const auto& t : patch.tris)
        for (int k = 0; k < 3; ++k) {
          const int32_t v = t[size_t(k)];
          if (size_t(v) < first_new) continue;
          for (int j = 1; j < 3; ++j) {
            sum[size_t(v) - first_new] = sum[size_t(v) - first_new] + patch.p(t[size_t(k + j) % 3]);
            ++count[size_t(v) - first_new];
          }
        }
      for (size_t i = 0; i < added; ++i)
        if (count[i] > 0) put(mesh.points, int32_t(first_new + i), (1.0 / count[i]) * sum[i]);
      patch.flip_to_delaunay();
    }
    HoleFill& r = result[l];
    r.filled = true;
    r.vertices_added = added;
    r.triangles_added = patch.tris.size();
    r.min_angle = 180;
    int32_t label = 0;
    if (labels) {
      auto it = triangle_on.find({loop[0], loop[1 % n]});
      label = it != triangle_on.end() ? (*labels)[size_t(it->second)] : (*labels)[0];
    }
    for (const auto& t : patch.tris) {
      mesh.triangles.insert(mesh.triangles.end(), t.begin(), t.end());
      if (labels) labels->push_back(label);
      r.min_angle = std::min(r.min_angle, min_angle(patch.p(t[0]), patch.p(t[1]), patch.p(t[2])) *
                                              180 / std::numbers::pi);
    }
  }
  return result;
}

}  // namespace vm
