// Non-manifold edges and vertices split into manifold sheets (Gueziec et
// al., "Cutting and stitching", IEEE TVCG 2001, the cutting step): fins
// dropped, the triangles around each non-manifold edge paired in angular
// order, then every vertex duplicated once per triangle fan; a local twist
// cut out where a short orientation-reversing cycle of the dual graph (a
// search of the orientation double cover) shows one.
#include "core/mesh/manifold_repair.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <tuple>

#include "core/mesh/adjacency.h"
#include "core/mesh/repair.h"
#include "core/util/parallel.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

Vec3 centroid_of(const SurfaceMesh& m, int32_t t) {
  const auto& tri = m.triangles;
  return (1.0 / 3) * (at(m.points, tri[3 * size_t(t)]) + at(m.points, tri[3 * size_t(t) + 1]) +
                      at(m.points, tri[3 * size_t(t) + 2]));
}

/// The non-manifold half-edges grouped by undirected edge: (a, b, h) sorted,
/// a < b.
std::vector<std::tuple<int32_t, int32_t, int32_t>> nonmanifold_half_edges(
    const SurfaceMesh& m, const TriangleAdjacency& adj) {
  std::vector<std::tuple<int32_t, int32_t, int32_t>> out;
  for (size_t h = 0; h < adj.opposite.size(); ++h) {
    if (adj.opposite[h] != TriangleAdjacency::kNonManifold) continue;
    const int32_t a = half_edge_from(m, int32_t(h)), b = half_edge_to(m, int32_t(h));
    out.emplace_back(std::min(a, b), std::max(a, b), int32_t(h));
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// Calls f(first, last) for each run of equal (a, b) in a sorted list.
template <class F>
void for_each_edge(const std::vector<std::tuple<int32_t, int32_t, int32_t>>& hs, F f) {
  for (size_t i = 0; i < hs.size();) {
    size_t j = i;
    while (j < hs.size() && std::get<0>(hs[j]) == std::get<0>(hs[i]) &&
           std::get<1>(hs[j]) == std::get<1>(hs[i]))
      ++j;
    f(i, j);
    i = j;
  }
}

/// Removes fins: per non-manifold edge, triangles whose other two edges are
/// free, as long as two triangles stay on the edge. Returns true if any.
bool remove_fins(SurfaceMesh& mesh, std::vector<int32_t>* labels, ManifoldRepairStats& stats,
                 const TriangleAdjacency& adj) {
  if (adj.num_nonmanifold_edges == 0) return false;
  const auto hs = nonmanifold_half_edges(mesh, adj);
  std::vector<uint8_t> remove(mesh.num_triangles(), 0);
  bool any = false;
  for_each_edge(hs, [&](size_t i, size_t j) {
    size_t left = j - i;
    for (size_t k = i; k < j && left > 2; ++k) {
      const int32_t h = std::get<2>(hs[k]), t = h / 3;
      bool fin = true;
      for (int32_t g = 3 * t; g < 3 * t + 3; ++g)
        if (g != h && adj.opposite[size_t(g)] != TriangleAdjacency::kBoundary) fin = false;
      if (!fin || remove[size_t(t)]) continue;
      if (stats.fins_removed == 0) stats.fin_example = centroid_of(mesh, t);
      remove[size_t(t)] = 1;
      ++stats.fins_removed;
      --left;
      any = true;
    }
  });
  if (any) remove_triangles(mesh, remove, labels);
  return any;
}

/// Duplicates each vertex of `candidates` per fan, fans connected across
/// the half-edges that have a partner (partner[h] >= 0).
void split_fans(SurfaceMesh& mesh, const std::vector<int32_t>& partner,
                std::vector<int32_t> candidates, ManifoldRepairStats& stats) {
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  const TriangleAdjacency stars = build_vertex_stars(mesh);
  auto& tri = mesh.triangles;
  std::vector<int32_t> parent;
  for (int32_t v : candidates) {
    const int32_t begin = stars.star_offsets[size_t(v)], end = stars.star_offsets[size_t(v) + 1];
    const int32_t n = end - begin;
    if (n < 2) continue;
    parent.resize(size_t(n));
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int32_t i) {
      while (parent[size_t(i)] != i) i = parent[size_t(i)] = parent[size_t(parent[size_t(i)])];
      return i;
    };
    auto local = [&](int32_t t) {
      for (int32_t i = 0; i < n; ++i)
        if (stars.star[size_t(begin + i)] == t) return i;
      return -1;
    };
    for (int32_t i = 0; i < n; ++i) {
      const int32_t t = stars.star[size_t(begin + i)];
      for (int32_t h = 3 * t; h < 3 * t + 3; ++h) {
        if (half_edge_from(mesh, h) != v && half_edge_to(mesh, h) != v) continue;
        const int32_t p = partner[size_t(h)];
        if (p < 0) continue;
        const int32_t j = local(p / 3);
        if (j >= 0) parent[size_t(find(i))] = find(j);
      }
    }
    // The fan of the first triangle keeps v; each other fan gets a copy.
    std::vector<int32_t> copy_of_root(size_t(n), -1);
    copy_of_root[size_t(find(0))] = v;
    bool split = false;
    for (int32_t i = 0; i < n; ++i) {
      const int32_t r = find(i);
      if (copy_of_root[size_t(r)] < 0) {
        copy_of_root[size_t(r)] = int32_t(mesh.num_vertices());
        const Vec3 p = at(mesh.points, v);
        mesh.points.insert(mesh.points.end(), p.begin(), p.end());
        ++stats.vertex_copies;
        split = true;
      }
      const int32_t t = stars.star[size_t(begin + i)];
      for (int k = 0; k < 3; ++k)
        if (tri[3 * size_t(t) + size_t(k)] == v)
          tri[3 * size_t(t) + size_t(k)] = copy_of_root[size_t(r)];
    }
    if (split) {
      if (stats.vertices_split == 0) stats.vertex_example = at(mesh.points, v);
      ++stats.vertices_split;
    }
  }
}

}  // namespace

void split_nonmanifold_edges(SurfaceMesh& mesh, std::vector<int32_t>* labels,
                             ManifoldRepairStats& stats, TriangleAdjacency* given) {
  if (labels && labels->size() != mesh.num_triangles()) labels = nullptr;
  TriangleAdjacency own;
  TriangleAdjacency& adj = given ? *given : own;
  if (!given) adj = build_adjacency(mesh);
  for (int round = 0; round < 4 && remove_fins(mesh, labels, stats, adj); ++round)
    adj = build_adjacency(mesh);
  if (adj.num_nonmanifold_edges == 0) return;
  std::vector<int32_t> partner = adj.opposite;
  std::vector<int32_t> ends;
  const auto hs = nonmanifold_half_edges(mesh, adj);
  for_each_edge(hs, [&](size_t i, size_t j) {
    const int32_t a = std::get<0>(hs[i]), b = std::get<1>(hs[i]);
    const Vec3 pa = at(mesh.points, a), d = normalized(at(mesh.points, b) - pa);
    const size_t n = j - i;
    // Each triangle's third corner as an angle around the edge, and whether
    // it runs a -> b.
    std::vector<double> angle(n);
    std::vector<int> forward(n);
    Vec3 u{}, w{};
    for (size_t k = 0; k < n; ++k) {
      const int32_t h = std::get<2>(hs[i + k]);
      const int32_t t = h / 3;
      int32_t c = -1;
      for (int q = 0; q < 3; ++q) {
        const int32_t x = mesh.triangles[3 * size_t(t) + size_t(q)];
        if (x != a && x != b) c = x;
      }
      Vec3 r = at(mesh.points, c) - pa;
      r = r - dot(r, d) * d;
      if (k == 0) {
        u = normalized(r);
        w = cross(d, u);
      }
      angle[k] = pm::atan2(dot(r, w), dot(r, u));
      forward[k] = half_edge_from(mesh, h) == a;
    }
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t x, size_t y) { return angle[x] < angle[y]; });
    // Pairings: consecutive in angular order, starting after `skip` (odd
    // counts: the skipped triangle stays unpaired) or at offset 0 / 1.
    auto pairs_of = [&](size_t start, size_t count) {
      std::vector<std::pair<size_t, size_t>> p;
      for (size_t k = 0; k + 1 < count; k += 2)
        p.emplace_back(order[(start + k) % n], order[(start + k + 1) % n]);
      return p;
    };
    // Score: pairs traversing the edge in opposite directions (a consistent
    // sheet) first, then pairs whose wedge (counterclockwise from x to y
    // around a -> b) is the inside of a solid, so each pair closes its own
    // lumen: a triangle running a -> b has the normal d x r, turned
    // counterclockwise from r, so both normals point out of the wedge when
    // x runs b -> a and y runs a -> b.
    std::vector<std::pair<size_t, size_t>> best;
    int best_score = -1;
    for (size_t start = 0; start < (n % 2 ? n : 2); ++start) {
      const auto p = n % 2 ? pairs_of(start + 1, n - 1) : pairs_of(start, n);
      int score = 0;
      for (auto [x, y] : p)
        score += int(n) * (forward[x] != forward[y]) + (!forward[x] && forward[y]);
      if (score > best_score) best_score = score, best = p;
    }
    for (auto [x, y] : best) {
      const int32_t hx = std::get<2>(hs[i + x]), hy = std::get<2>(hs[i + y]);
      partner[size_t(hx)] = hy;
      partner[size_t(hy)] = hx;
    }
    if (n % 2)
      for (size_t k = 0; k < n; ++k)
        if (partner[size_t(std::get<2>(hs[i + k]))] == TriangleAdjacency::kNonManifold)
          partner[size_t(std::get<2>(hs[i + k]))] = TriangleAdjacency::kBoundary;
    if (stats.edges_split == 0) stats.edge_example = 0.5 * (pa + at(mesh.points, b));
    ++stats.edges_split;
    ends.push_back(a);
    ends.push_back(b);
  });
  split_fans(mesh, partner, std::move(ends), stats);
  if (given) *given = build_adjacency(mesh);
}

namespace {

/// Whether orienting every component is contradictory somewhere: a
/// breadth-first propagation of relative orientations across the edges of
/// exactly two triangles meets a triangle from both sides.
bool orientation_contradicts(const SurfaceMesh& mesh, const TriangleAdjacency& adj) {
  // Usually every shared edge runs opposite ways already: every triangle
  // keeps its side, and there is nothing to propagate.
  const size_t disagreeing =
      parallel_sum<size_t>(adj.opposite.size(), size_t(3) << 16, [&](size_t b, size_t e) {
        size_t n = 0;
        for (size_t h = b; h < e; ++h) {
          const int32_t o = adj.opposite[h];
          n += o >= 0 && half_edge_from(mesh, int32_t(h)) == half_edge_from(mesh, o);
        }
        return n;
      });
  if (disagreeing == 0) return false;
  const size_t nt = mesh.num_triangles();
  std::vector<int8_t> side(nt, -1);  // 0: as given, 1: reversed; -1 unseen
  std::vector<int32_t> queue;
  for (size_t seed = 0; seed < nt; ++seed) {
    if (side[seed] >= 0) continue;
    side[seed] = 0;
    queue.assign(1, int32_t(seed));
    for (size_t q = 0; q < queue.size(); ++q) {
      const int32_t t = queue[q];
      for (int32_t h = 3 * t; h < 3 * t + 3; ++h) {
        const int32_t o = adj.opposite[size_t(h)];
        if (o < 0) continue;
        // Consistent when the shared edge runs opposite ways once both
        // triangles are turned to their sides.
        const int8_t want =
            int8_t(side[size_t(t)] ^ (half_edge_from(mesh, h) == half_edge_from(mesh, o)));
        const int32_t u = o / 3;
        if (side[size_t(u)] < 0) {
          side[size_t(u)] = want;
          queue.push_back(u);
        } else if (side[size_t(u)] != want) {
          return true;
        }
      }
    }
  }
  return false;
}

/// The triangles on a short orientation-reversing cycle (at most
/// 2 `depth` triangles across edges of exactly two triangles): a search of
/// the orientation double cover from (t, as given) that reaches (t,
/// reversed) within `depth` steps each way. A Moebius band's shortest such
/// cycle runs its whole length, a local twist's is a few triangles.
std::vector<int32_t> twisted_triangles(const SurfaceMesh& mesh, const TriangleAdjacency& adj,
                                       int depth) {
  const size_t nt = mesh.num_triangles();
  std::vector<int32_t> stamp(2 * nt, -1);  // per (triangle, side): last search
  std::vector<std::pair<int32_t, int>> level, next;
  std::vector<int32_t> out;
  for (size_t t = 0; t < nt; ++t) {
    level.assign(1, {int32_t(t), 0});
    stamp[2 * t] = int32_t(t);
    bool found = false;
    for (int d = 0; d < 2 * depth && !found && !level.empty(); ++d) {
      next.clear();
      for (auto [x, side] : level) {
        for (int32_t h = 3 * x; h < 3 * x + 3 && !found; ++h) {
          const int32_t o = adj.opposite[size_t(h)];
          if (o < 0) continue;
          const int32_t u = o / 3;
          const int s2 = side ^ int(half_edge_from(mesh, h) == half_edge_from(mesh, o));
          if (size_t(u) == t && s2 == 1) found = true;
          int32_t& st = stamp[2 * size_t(u) + size_t(s2)];
          if (st == int32_t(t)) continue;
          st = int32_t(t);
          next.emplace_back(u, s2);
        }
      }
      level.swap(next);
    }
    if (found) out.push_back(int32_t(t));
  }
  return out;
}

}  // namespace

size_t remove_orientation_twists(SurfaceMesh& mesh, std::vector<int32_t>* labels,
                                 ManifoldRepairStats& stats, size_t budget,
                                 TriangleAdjacency* given) {
  if (labels && labels->size() != mesh.num_triangles()) labels = nullptr;
  std::vector<Vec3> rim;
  {
    TriangleAdjacency own;
    const TriangleAdjacency& adj = given ? *given : (own = build_adjacency(mesh));
    if (!orientation_contradicts(mesh, adj)) return 0;  // the usual case
    // The input's free-edge vertices, by position (removals renumber): no
    // triangle touching them goes, so a band is never cut across.
    for (size_t h = 0; h < adj.opposite.size(); ++h)
      if (adj.opposite[h] == TriangleAdjacency::kBoundary)
        rim.push_back(at(mesh.points, half_edge_from(mesh, int32_t(h))));
    std::sort(rim.begin(), rim.end());
  }
  const SurfaceMesh original = mesh;
  const std::vector<int32_t> original_labels = labels ? *labels : std::vector<int32_t>{};
  size_t removed = 0;
  Vec3 example{};
  for (int round = 0; round < 4; ++round) {
    const TriangleAdjacency adj = build_adjacency(mesh);
    if (!orientation_contradicts(mesh, adj)) {
      if (removed > 0) {
        if (stats.twisted_removed == 0) stats.twisted_example = example;
        stats.twisted_removed += removed;
      }
      if (given) *given = adj;
      return removed;
    }
    const std::vector<int32_t> twisted = twisted_triangles(mesh, adj, 3);
    bool on_rim = false;
    for (int32_t t : twisted)
      for (int k = 0; k < 3; ++k)
        on_rim |= std::binary_search(rim.begin(), rim.end(),
                                     at(mesh.points, mesh.triangles[3 * size_t(t) + size_t(k)]));
    if (round == 3 || twisted.empty() || on_rim || removed + twisted.size() > budget) break;
    if (removed == 0) example = centroid_of(mesh, twisted[0]);
    std::vector<uint8_t> remove(mesh.num_triangles(), 0);
    for (int32_t t : twisted) remove[size_t(t)] = 1;
    remove_triangles(mesh, remove, labels);
    removed += twisted.size();
  }
  mesh = original;
  if (labels) *labels = original_labels;
  return 0;
}

void split_nonmanifold_vertices(SurfaceMesh& mesh, ManifoldRepairStats& stats,
                                const TriangleAdjacency* given) {
  TriangleAdjacency own;
  const TriangleAdjacency& adj = given ? *given : (own = build_adjacency(mesh));
  // Every vertex: counting a star's fans costs about as much as finding
  // the candidates would.
  std::vector<int32_t> all(mesh.num_vertices());
  std::iota(all.begin(), all.end(), 0);
  split_fans(mesh, adj.opposite, std::move(all), stats);
}

}  // namespace vm
