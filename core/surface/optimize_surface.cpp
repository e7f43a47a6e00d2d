// Surface mesh optimization on the input surface (Marchandise et al. 2.1):
// phases per pass are edge swaps (maximizing the worse gamma_k of the pair,
// Lawson-like but by quality) and Laplacian smoothing projected back onto
// the input by a local closest-point walk.
#include "core/surface/optimize_surface.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/geom/closest_point.h"
#include "core/quality/triangle_quality.h"

namespace vm {
namespace {

struct Vec {
  double x[3];
};

Vec normal(const double* a, const double* b, const double* c) {
  double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
         w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  Vec n{{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]}};
  double l = std::sqrt(n.x[0] * n.x[0] + n.x[1] * n.x[1] + n.x[2] * n.x[2]);
  if (l > 0)
    for (double& v : n.x) v /= l;
  return n;
}

double dot(const Vec& a, const Vec& b) {
  return a.x[0] * b.x[0] + a.x[1] * b.x[1] + a.x[2] * b.x[2];
}

class Optimizer {
 public:
  Optimizer(SurfaceMesh& m, std::vector<int32_t>& home, const std::vector<uint8_t>& fixed,
            const SurfaceMesh& input, const TriangleAdjacency& input_adj,
            const SurfaceOptimizeOptions& o)
      : m_(m), home_(home), fixed_(fixed), in_(input), in_adj_(input_adj) {
    cos_turn_ = std::cos(o.max_normal_turn_degrees * std::numbers::pi / 180);
    vt_.assign(m.num_vertices(), {});
    for (size_t t = 0; t < m.num_triangles(); ++t)
      for (int c = 0; c < 3; ++c) vt_[size_t(m.triangles[3 * t + c])].push_back(int32_t(t));
  }

  size_t swap_pass() {
    size_t swaps = 0;
    for (int32_t t = 0; t < int32_t(m_.num_triangles()); ++t)
      for (int k = 0; k < 3; ++k)
        if (try_swap(t, k)) {
          ++swaps;
          break;
        }
    return swaps;
  }

  size_t smooth_pass() {
    size_t moves = 0;
    for (size_t v = 0; v < m_.num_vertices(); ++v)
      if (!fixed_[v] && try_move(int32_t(v))) ++moves;
    return moves;
  }

 private:
  const double* p(int32_t v) const { return &m_.points[3 * size_t(v)]; }
  int32_t* tri(int32_t t) { return &m_.triangles[3 * size_t(t)]; }
  double gamma(int32_t a, int32_t b, int32_t c) const { return triangle_gamma(p(a), p(b), p(c)); }

  /// The other triangle with edge (b, a), or -1.
  int32_t across(int32_t t, int32_t a, int32_t b) const {
    int32_t found = -1;
    for (int32_t u : vt_[size_t(a)]) {
      if (u == t) continue;
      const int32_t* U = &m_.triangles[3 * size_t(u)];
      for (int c = 0; c < 3; ++c)
        if (U[c] == b && U[(c + 1) % 3] == a) {
          if (found >= 0) return -1;  // non-manifold: leave it alone
          found = u;
        }
    }
    return found;
  }

  bool has_edge(int32_t a, int32_t b) const {
    for (int32_t u : vt_[size_t(a)]) {
      const int32_t* U = &m_.triangles[3 * size_t(u)];
      if (U[0] == b || U[1] == b || U[2] == b) return true;
    }
    return false;
  }

  static void erase(std::vector<int32_t>& list, int32_t x) {
    list.erase(std::find(list.begin(), list.end(), x));
  }

  // t = (a, b, c), u = (b, a, d) -> t = (a, d, c), u = (d, b, c).
  bool try_swap(int32_t t, int k) {
    int32_t* T = tri(t);
    const int32_t a = T[k], b = T[(k + 1) % 3], c = T[(k + 2) % 3];
    const int32_t u = across(t, a, b);
    if (u < 0) return false;
    int32_t* U = tri(u);
    int32_t d = -1;
    for (int j = 0; j < 3; ++j)
      if (U[j] != a && U[j] != b) d = U[j];
    if (d < 0 || d == c || has_edge(c, d)) return false;
    const double before = std::min(gamma(a, b, c), gamma(b, a, d));
    const double after = std::min(gamma(a, d, c), gamma(d, b, c));
    if (!(after > before + 1e-9)) return false;
    const Vec nt = normal(p(a), p(b), p(c)), nu = normal(p(b), p(a), p(d));
    const Vec n1 = normal(p(a), p(d), p(c)), n2 = normal(p(d), p(b), p(c));
    if (dot(nt, nu) < cos_turn_ || dot(n1, n2) < cos_turn_) return false;
    for (const Vec& n : {n1, n2})
      if (dot(n, nt) < cos_turn_ || dot(n, nu) < cos_turn_) return false;
    T[0] = a, T[1] = d, T[2] = c;
    U[0] = d, U[1] = b, U[2] = c;
    erase(vt_[size_t(a)], u);
    erase(vt_[size_t(b)], t);
    vt_[size_t(c)].push_back(u);
    vt_[size_t(d)].push_back(t);
    return true;
  }

  bool try_move(int32_t v) {
    const auto& star = vt_[size_t(v)];
    if (star.empty()) return false;
    // Target: the mean of the apexes that would make each star triangle
    // equilateral on its opposite edge, in its own plane.
    double target[3] = {0, 0, 0};
    double before = 1, before_sum = 0;
    for (int32_t t : star) {
      const int32_t* T = tri(t);
      const double g = gamma(T[0], T[1], T[2]);
      before = std::min(before, g);
      before_sum += g;
      int c = 0;
      while (T[c] != v) ++c;
      const double *b = p(T[(c + 1) % 3]), *e = p(T[(c + 2) % 3]);
      const Vec n = normal(p(v), b, e);
      const double d[3] = {e[0] - b[0], e[1] - b[1], e[2] - b[2]};
      const double side[3] = {n.x[1] * d[2] - n.x[2] * d[1], n.x[2] * d[0] - n.x[0] * d[2],
                              n.x[0] * d[1] - n.x[1] * d[0]};  // |side| = |d|, into the triangle
      for (int k = 0; k < 3; ++k) target[k] += 0.5 * (b[k] + e[k]) + 0.8660254037844386 * side[k];
    }
    for (double& x : target) x /= double(star.size());
    double projected[3];
    const int32_t new_home = project_near(target, home_[size_t(v)], in_, in_adj_, projected);
    double* pv = &m_.points[3 * size_t(v)];
    const double old[3] = {pv[0], pv[1], pv[2]};
    old_normals_.clear();
    for (int32_t t : star) {
      const int32_t* T = tri(t);
      old_normals_.push_back(normal(p(T[0]), p(T[1]), p(T[2])));
    }
    std::copy(projected, projected + 3, pv);
    double after = 1, after_sum = 0;
    bool ok = true;
    for (size_t i = 0; i < star.size() && ok; ++i) {
      const int32_t* T = tri(star[i]);
      const double g = gamma(T[0], T[1], T[2]);
      after = std::min(after, g);
      after_sum += g;
      ok = dot(normal(p(T[0]), p(T[1]), p(T[2])), old_normals_[i]) >= cos_turn_;
    }
    // Better worst triangle, or the same worst and a better mean.
    const bool better = after > before + 1e-9 || (after >= before && after_sum > before_sum + 1e-9);
    if (!ok || !better) {
      std::copy(old, old + 3, pv);
      return false;
    }
    home_[size_t(v)] = new_home;
    return true;
  }

  SurfaceMesh& m_;
  std::vector<int32_t>& home_;
  const std::vector<uint8_t>& fixed_;
  const SurfaceMesh& in_;
  const TriangleAdjacency& in_adj_;
  double cos_turn_ = 0;
  std::vector<std::vector<int32_t>> vt_;
  std::vector<Vec> old_normals_;
};

}  // namespace

int32_t project_near(const double* q, int32_t start, const SurfaceMesh& input,
                     const TriangleAdjacency& adj, double* out) {
  auto dist2 = [&](int32_t t, double* x) {
    const int32_t* T = &input.triangles[3 * size_t(t)];
    return closest_point_on_triangle(q, &input.points[3 * size_t(T[0])],
                                     &input.points[3 * size_t(T[1])],
                                     &input.points[3 * size_t(T[2])], x);
  };
  double best_point[3];
  const double radius2 = dist2(start, best_point);
  double best = radius2;
  int32_t best_t = start;
  // Breadth-first over triangles within the start triangle's distance.
  std::vector<int32_t> queue = {start};
  for (size_t i = 0; i < queue.size() && queue.size() < 512; ++i) {
    const int32_t t = queue[i];
    for (int k = 0; k < 3; ++k) {
      const int32_t o = adj.opposite[3 * size_t(t) + k];
      if (o < 0) continue;
      const int32_t u = o / 3;
      if (std::find(queue.begin(), queue.end(), u) != queue.end()) continue;
      double x[3];
      const double d = dist2(u, x);
      if (d > radius2) continue;
      queue.push_back(u);
      if (d < best) {
        best = d;
        best_t = u;
        std::copy(x, x + 3, best_point);
      }
    }
  }
  std::copy(best_point, best_point + 3, out);
  return best_t;
}

SurfaceOptimizeStats optimize_on_surface(SurfaceMesh& mesh, std::vector<int32_t>& home,
                                         const std::vector<uint8_t>& fixed,
                                         const SurfaceMesh& input,
                                         const TriangleAdjacency& input_adj,
                                         const SurfaceOptimizeOptions& options) {
  SurfaceOptimizeStats stats;
  Optimizer opt(mesh, home, fixed, input, input_adj, options);
  for (int pass = 0; pass < options.passes; ++pass) {
    size_t swaps = opt.swap_pass();
    size_t moves = opt.smooth_pass();
    stats.swaps += swaps;
    stats.moves += moves;
    if (swaps == 0 && moves == 0) break;
  }
  return stats;
}

}  // namespace vm
