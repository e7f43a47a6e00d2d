// Planar mesh optimization: Lawson flips toward the Delaunay triangulation
// of the current points, and constrained Laplacian smoothing (a move is kept
// only if the star stays valid and its worst triangle quality, gamma of the
// seed's section 3, does not decrease).
#include "core/mesh2d/optimize2d.h"

#include <algorithm>
#include <cstdint>

#include "core/geom/predicates.h"
#include "core/geom/triangle_gamma.h"

namespace vm {
namespace {

double gamma2d(const double* a, const double* b, const double* c) {
  const double p[3] = {a[0], a[1], 0}, q[3] = {b[0], b[1], 0}, r[3] = {c[0], c[1], 0};
  return triangle_gamma(p, q, r);
}

// One use of an edge by a triangle: the edge's key (min << 32 | max), the
// triangle and the local index of the corner opposite the edge.
struct EdgeUse {
  uint64_t key;
  int32_t t;
  int k;
};

// Every use of every edge, sorted by key, so the uses of an edge are
// consecutive.
std::vector<EdgeUse> edge_uses(const Mesh2D& m) {
  std::vector<EdgeUse> e;
  e.reserve(m.triangles.size());
  for (int32_t t = 0; t < int32_t(m.num_triangles()); ++t)
    for (int k = 0; k < 3; ++k) {
      auto [a, b] = std::minmax(m.triangles[3 * size_t(t) + size_t((k + 1) % 3)],
                                m.triangles[3 * size_t(t) + size_t((k + 2) % 3)]);
      e.push_back({(uint64_t(uint32_t(a)) << 32) | uint32_t(b), t, k});
    }
  std::sort(e.begin(), e.end(), [](const EdgeUse& x, const EdgeUse& y) { return x.key < y.key; });
  return e;
}

// Calls f(first use, number of uses) for each edge.
template <class F>
void for_each_edge(const std::vector<EdgeUse>& uses, F&& f) {
  for (size_t i = 0; i < uses.size();) {
    size_t j = i + 1;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    f(&uses[i], j - i);
    i = j;
  }
}

// One Lawson sweep over the edges; `uses`: edge_uses(m), recomputed here
// when a flip changed the triangles (smoothing moves points only, so the
// uses stay valid across it).
size_t flip_pass(Mesh2D& m, std::vector<EdgeUse>& uses) {
  size_t flips = 0;
  std::vector<uint8_t> touched(m.num_triangles(), 0);
  auto P = [&](int32_t v) { return &m.points[2 * size_t(v)]; };
  for_each_edge(uses, [&](const EdgeUse* use, size_t count) {
    if (count != 2) return;
    const int32_t t = use[0].t, u = use[1].t;
    const int k = use[0].k, j = use[1].k;
    if (touched[size_t(t)] || touched[size_t(u)]) return;  // stale: handled next pass
    int32_t* T = &m.triangles[3 * size_t(t)];
    int32_t* U = &m.triangles[3 * size_t(u)];
    int32_t p = T[k], a = T[(k + 1) % 3], b = T[(k + 2) % 3], q = U[j];
    if (incircle(P(p), P(a), P(b), P(q)) <= 0) return;
    // q inside the circumcircle of (p, a, b): the quad is convex; flip a-b
    // to p-q keeping both triangles counterclockwise.
    if (orient2d(P(p), P(a), P(q)) <= 0 || orient2d(P(q), P(b), P(p)) <= 0) return;
    T[0] = p, T[1] = a, T[2] = q;
    U[0] = q, U[1] = b, U[2] = p;
    touched[size_t(t)] = touched[size_t(u)] = 1;
    ++flips;
  });
  if (flips > 0) uses = edge_uses(m);
  return flips;
}

}  // namespace

Optimize2DStats optimize_mesh2d(Mesh2D& m, int passes) {
  Optimize2DStats stats;
  const size_t nv = m.num_vertices();
  std::vector<EdgeUse> uses = edge_uses(m);
  for (int pass = 0; pass < passes; ++pass) {
    for (int sweep = 0; sweep < 8; ++sweep) {
      size_t f = flip_pass(m, uses);
      stats.flips += f;
      if (f == 0) break;
    }
    // Boundary vertices: on an edge used by a single triangle.
    std::vector<uint8_t> fixed(nv, 0);
    std::vector<std::vector<int32_t>> neighbors(nv), star(nv);
    for_each_edge(uses, [&](const EdgeUse* use, size_t count) {
      const int32_t a = int32_t(use->key >> 32), b = int32_t(use->key & 0xffffffffu);
      if (count == 1) fixed[size_t(a)] = fixed[size_t(b)] = 1;
      neighbors[size_t(a)].push_back(b);
      neighbors[size_t(b)].push_back(a);
    });
    for (int32_t t = 0; t < int32_t(m.num_triangles()); ++t)
      for (int k = 0; k < 3; ++k) star[m.triangles[3 * size_t(t) + k]].push_back(t);
    auto worst = [&](int32_t v) {
      double w = 1;
      for (int32_t t : star[v]) {
        const int32_t* T = &m.triangles[3 * size_t(t)];
        const double *a = &m.points[2 * size_t(T[0])], *b = &m.points[2 * size_t(T[1])],
                     *c = &m.points[2 * size_t(T[2])];
        if (orient2d(a, b, c) <= 0) return -1.0;
        w = std::min(w, gamma2d(a, b, c));
      }
      return w;
    };
    for (size_t v = 0; v < nv; ++v) {
      if (fixed[v] || neighbors[v].empty()) continue;
      double c[2] = {0, 0};
      for (int32_t n : neighbors[v]) {
        c[0] += m.points[2 * size_t(n)] / double(neighbors[v].size());
        c[1] += m.points[2 * size_t(n) + 1] / double(neighbors[v].size());
      }
      double before = worst(int32_t(v));
      double old[2] = {m.points[2 * v], m.points[2 * v + 1]};
      m.points[2 * v] = c[0];
      m.points[2 * v + 1] = c[1];
      if (worst(int32_t(v)) < before) {
        m.points[2 * v] = old[0];
        m.points[2 * v + 1] = old[1];
      } else {
        ++stats.moves;
      }
    }
  }
  for (int sweep = 0; sweep < 8 && flip_pass(m, uses) > 0; ++sweep) ++stats.flips;
  return stats;
}

}  // namespace vm
