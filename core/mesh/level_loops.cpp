// Level curves of a vertex field by marching triangles (level_loops.h).
#include "core/mesh/level_loops.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/geom/vec3.h"

namespace vm {

std::vector<LevelLoop> level_loops(const SurfaceMesh& mesh, const TriangleAdjacency& adj,
                                   std::span<const double> field, double value,
                                   std::span<const int32_t> triangles) {
  const int32_t* tri = mesh.triangles.data();
  auto above = [&](int32_t v) { return field[size_t(v)] > value; };
  auto count_above = [&](int32_t t) {
    return int(above(tri[3 * t])) + int(above(tri[3 * t + 1])) + int(above(tri[3 * t + 2]));
  };
  std::vector<int32_t> mixed;
  auto consider = [&](int32_t t) {
    const int n = count_above(t);
    if (n == 1 || n == 2) mixed.push_back(t);
  };
  if (triangles.empty()) {
    for (size_t t = 0; t < mesh.num_triangles(); ++t) consider(int32_t(t));
  } else {
    for (int32_t t : triangles) consider(t);
    std::sort(mixed.begin(), mixed.end());
    mixed.erase(std::unique(mixed.begin(), mixed.end()), mixed.end());
  }
  auto index_of = [&](int32_t t) -> long {
    auto it = std::lower_bound(mixed.begin(), mixed.end(), t);
    return it != mixed.end() && *it == t ? long(it - mixed.begin()) : -1;
  };
  // The half-edge of t going from above to below (entry) or below to above
  // (exit); a mixed triangle has exactly one of each.
  auto crossing = [&](int32_t t, bool exit) {
    for (int k = 0; k < 3; ++k) {
      const int32_t h = 3 * t + k;
      const bool from = above(half_edge_from(mesh, h)), to = above(half_edge_to(mesh, h));
      if (from != to && to == exit) return h;
    }
    return int32_t(-1);
  };
  // The triangle across half-edge h if it is mixed and searched, else -1.
  auto across = [&](int32_t h) -> int32_t {
    const int32_t o = adj.opposite[size_t(h)];
    if (o < 0) return -1;
    return index_of(o / 3) >= 0 ? o / 3 : -1;
  };
  auto add_point = [&](LevelLoop& loop, int32_t h) {
    int32_t b = half_edge_from(mesh, h), a = half_edge_to(mesh, h);
    if (above(b)) std::swap(a, b);
    loop.edges.push_back({b, a});
    const double fb = field[size_t(b)], fa = field[size_t(a)];
    const double s = fb == value ? 0.0 : (value - fb) / (fa - fb);
    const double* pb = &mesh.points[3 * size_t(b)];
    const double* pa = &mesh.points[3 * size_t(a)];
    for (int k = 0; k < 3; ++k) loop.points.push_back(pb[k] + s * (pa[k] - pb[k]));
  };

  std::vector<LevelLoop> loops;
  std::vector<uint8_t> visited(mixed.size(), 0);
  for (size_t i = 0; i < mixed.size(); ++i) {
    if (visited[i]) continue;
    // Walk backward to the start of an open curve (or around a closed one).
    int32_t start = mixed[i];
    bool closed = false;
    for (size_t guard = 0; guard <= mixed.size(); ++guard) {
      const int32_t prev = across(crossing(start, false));
      if (prev < 0) break;
      if (prev == mixed[i]) {
        closed = true;
        start = mixed[i];
        break;
      }
      start = prev;
    }
    LevelLoop loop;
    loop.closed = closed;
    int32_t t = start;
    add_point(loop, crossing(t, false));
    for (size_t guard = 0; guard <= mixed.size(); ++guard) {
      visited[size_t(index_of(t))] = 1;
      loop.triangles.push_back(t);
      const int32_t h = crossing(t, true);
      const int32_t next = across(h);
      if (next < 0) {
        if (!closed) add_point(loop, h);
        break;
      }
      if (closed && next == start) break;
      add_point(loop, h);
      t = next;
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

CurveShape curve_shape(std::span<const double> points) {
  CurveShape s;
  const size_t n = points.size() / 3;
  if (n == 0) return s;
  auto p = [&](size_t i) { return &points[3 * (i % n)]; };
  for (size_t i = 0; i < n; ++i) {
    double e[3];
    v3::sub(p(i + 1), p(i), e);
    const double len = v3::norm(e);
    s.perimeter += len;
    for (int k = 0; k < 3; ++k) s.centroid[size_t(k)] += len * 0.5 * (p(i)[k] + p(i + 1)[k]);
  }
  if (s.perimeter > 0) {
    for (double& c : s.centroid) c /= s.perimeter;
  } else {
    for (int k = 0; k < 3; ++k) s.centroid[size_t(k)] = p(0)[k];
  }
  s.min_distance = 1e300;
  for (size_t i = 0; i < n; ++i) {
    double u[3], w[3], c[3];
    v3::sub(p(i), s.centroid.data(), u);
    v3::sub(p(i + 1), s.centroid.data(), w);
    v3::cross(u, w, c);
    for (int k = 0; k < 3; ++k) s.vector_area[size_t(k)] += 0.5 * c[k];
    const double r = v3::norm(u);
    s.min_distance = std::min(s.min_distance, r);
    s.max_distance = std::max(s.max_distance, r);
  }
  s.radius = std::sqrt(v3::norm(s.vector_area.data()) / std::numbers::pi);
  return s;
}

namespace {

/// Two unit vectors spanning the plane normal to n.
void plane_frame(const std::array<double, 3>& n, double* u, double* w) {
  const double a[3] = {std::abs(n[0]) < 0.6 ? 1.0 : 0.0, std::abs(n[0]) < 0.6 ? 0.0 : 1.0, 0.0};
  v3::cross(n.data(), a, u);
  const double len = v3::norm(u);
  for (int k = 0; k < 3; ++k) u[k] /= len;
  v3::cross(n.data(), u, w);
}

}  // namespace

int winding_number(std::span<const double> points, const std::array<double, 3>& q,
                   const std::array<double, 3>& normal) {
  double u[3], w[3];
  plane_frame(normal, u, w);
  const size_t n = points.size() / 3;
  int wn = 0;
  auto coords = [&](size_t i, double& x, double& y) {
    double d[3];
    v3::sub(&points[3 * (i % n)], q.data(), d);
    x = v3::dot(d, u);
    y = v3::dot(d, w);
  };
  for (size_t i = 0; i < n; ++i) {
    double x0, y0, x1, y1;
    coords(i, x0, y0);
    coords(i + 1, x1, y1);
    const double side = x0 * y1 - x1 * y0;  // > 0: q left of the edge
    if (y0 <= 0) {
      if (y1 > 0 && side > 0) ++wn;
    } else if (y1 <= 0 && side < 0) {
      --wn;
    }
  }
  return wn;
}

double distance_to_polygon(std::span<const double> points, const std::array<double, 3>& q) {
  const size_t n = points.size() / 3;
  double best = 1e300;
  for (size_t i = 0; i < n; ++i) {
    const double* a = &points[3 * i];
    const double* b = &points[3 * ((i + 1) % n)];
    double ab[3], aq[3];
    v3::sub(b, a, ab);
    v3::sub(q.data(), a, aq);
    const double len2 = v3::dot(ab, ab);
    const double t = len2 > 0 ? std::clamp(v3::dot(aq, ab) / len2, 0.0, 1.0) : 0.0;
    double d[3];
    for (int k = 0; k < 3; ++k) d[k] = aq[k] - t * ab[k];
    best = std::min(best, v3::norm(d));
  }
  return best;
}

}  // namespace vm
