// Safe surface repairs. Orientation follows the usual breadth-first
// propagation across manifold edges (each shared edge must be traversed in
// opposite directions), then each component is turned outward by the sign of
// its enclosed volume, openings closed by fans to their centroids.
#include "core/mesh/repair.h"

#include <algorithm>
#include <array>

#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"
#include "core/util/concurrent_union_find.h"
#include "core/util/parallel.h"

namespace vm {
namespace {

/// Chunk of the loops over triangles or vertices (parallel.h).
constexpr size_t kGrain = size_t(1) << 16;

bool zero_area(const SurfaceMesh& m, size_t t) {
  const double* a = &m.points[3 * m.triangles[3 * t]];
  const double* b = &m.points[3 * m.triangles[3 * t + 1]];
  const double* c = &m.points[3 * m.triangles[3 * t + 2]];
  double u[3], v[3];
  for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], v[k] = c[k] - a[k];
  return u[1] * v[2] - u[2] * v[1] == 0 && u[2] * v[0] - u[0] * v[2] == 0 &&
         u[0] * v[1] - u[1] * v[0] == 0;
}

Vec3 centroid(const SurfaceMesh& m, size_t t) {
  return (1.0 / 3) * (at(m.points, m.triangles[3 * t]) + at(m.points, m.triangles[3 * t + 1]) +
                      at(m.points, m.triangles[3 * t + 2]));
}

/// Drops the vertices no triangle uses; returns old -> new index (-1: gone).
std::vector<int32_t> remove_unused_vertices(SurfaceMesh& mesh, RepairStats& stats) {
  std::vector<int32_t> remap(mesh.num_vertices(), -1);
  for (int32_t v : mesh.triangles) remap[v] = 0;
  int32_t next = 0;
  for (size_t v = 0; v < remap.size(); ++v) {
    if (remap[v] < 0) continue;
    remap[v] = next;
    for (int k = 0; k < 3; ++k) mesh.points[3 * next + k] = mesh.points[3 * v + k];
    ++next;
  }
  stats.unused_vertices_removed += remap.size() - size_t(next);
  if (size_t(next) == remap.size()) return remap;  // all used: nothing moved
  mesh.points.resize(3 * size_t(next));
  for (int32_t& v : mesh.triangles) v = remap[v];
  return remap;
}

/// Keeps the triangles with keep[t] != 0 (and their labels), in order.
void keep_triangles(SurfaceMesh& mesh, const std::vector<uint8_t>& keep,
                    std::vector<int32_t>* labels) {
  auto& tri = mesh.triangles;
  size_t out = 0;
  for (size_t t = 0; t < keep.size(); ++t) {
    if (!keep[t]) continue;
    for (int k = 0; k < 3; ++k) tri[3 * out + k] = tri[3 * t + k];
    if (labels) (*labels)[out] = (*labels)[t];
    ++out;
  }
  tri.resize(3 * out);
  if (labels) labels->resize(out);
}

// Union-find over triangles where each triangle also stores whether its
// orientation is reversed relative to its parent, so that the relative
// orientation of any two triangles of a tree is the xor along their paths.
class ParityUnionFind {
 public:
  explicit ParityUnionFind(size_t n) : parent_(n), parity_(n, 0), size_(n, 1) {
    for (size_t i = 0; i < n; ++i) parent_[i] = int32_t(i);
  }
  /// Root of t, and t's parity relative to it (with path compression).
  std::pair<int32_t, uint8_t> find(int32_t t) {
    int32_t root = t;
    uint8_t p = 0;
    while (parent_[root] != root) {
      p ^= parity_[root];
      root = parent_[root];
    }
    // Second pass: point the path at the root with the right parities.
    uint8_t rest = p;
    while (parent_[t] != root && t != root) {
      int32_t next = parent_[t];
      uint8_t own = parity_[t];
      parent_[t] = root;
      parity_[t] = rest;
      rest ^= own;
      t = next;
    }
    return {root, p};
  }
  /// Records that t and s have relative parity `rel`; false on contradiction.
  bool unite(int32_t t, int32_t s, uint8_t rel) {
    auto [rt, pt] = find(t);
    auto [rs, ps] = find(s);
    if (rt == rs) return (pt ^ ps) == rel;
    if (size_[rt] < size_[rs]) std::swap(rt, rs);
    parent_[rs] = rt;
    parity_[rs] = pt ^ ps ^ rel;
    size_[rt] += size_[rs];
    return true;
  }

 private:
  std::vector<int32_t> parent_;
  std::vector<uint8_t> parity_;
  std::vector<int32_t> size_;
};

// Removes each triangle t = (a, b, c) whose corners are distinct but
// collinear (c strictly inside the longest edge a-b) by splitting its
// neighbor s across a-b at c into two triangles with s's orientation, which
// keeps the surface closed: dropping t alone would open a slit. A few passes
// handle chains; flat triangles left then (no single neighbor across the
// long edge, or a flat neighbor) are dropped and counted as degenerate.
void repair_collinear_triangles(SurfaceMesh& mesh, RepairStats& stats,
                                std::vector<int32_t>* labels) {
  auto& tri = mesh.triangles;
  for (int pass = 0; pass < 4; ++pass) {
    const std::vector<int32_t> flat =
        parallel_select(mesh.num_triangles(), kGrain, [&](size_t t) { return zero_area(mesh, t); });
    if (flat.empty()) return;
    const bool last_pass = pass == 3;
    // Vertex -> triangles, for the neighbors of the flat triangles.
    const size_t nv = mesh.num_vertices();
    std::vector<int32_t> off(nv + 1, 0), star(tri.size());
    for (int32_t v : tri) ++off[v + 1];
    for (size_t v = 0; v < nv; ++v) off[v + 1] += off[v];
    std::vector<int32_t> fill(off.begin(), off.end() - 1);
    for (size_t t = 0; t < mesh.num_triangles(); ++t)
      for (int k = 0; k < 3; ++k) star[fill[tri[3 * t + k]]++] = int32_t(t);
    std::vector<uint8_t> touched(mesh.num_triangles(), 0), remove(mesh.num_triangles(), 0);
    for (int32_t t : flat) touched[t] = 1;
    size_t progress = 0;
    for (int32_t t : flat) {
      // Longest edge (a, b) and the middle corner c.
      int32_t best = 0;
      double best_len = -1;
      for (int k = 0; k < 3; ++k) {
        const double* p = &mesh.points[3 * tri[3 * t + k]];
        const double* q = &mesh.points[3 * tri[3 * t + (k + 1) % 3]];
        double d = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                   (p[2] - q[2]) * (p[2] - q[2]);
        if (d > best_len) best_len = d, best = k;
      }
      int32_t a = tri[3 * t + best], b = tri[3 * t + (best + 1) % 3];
      int32_t c = tri[3 * t + (best + 2) % 3];
      int32_t neighbor = -1, count = 0;
      for (int32_t i = off[a]; i < off[a + 1]; ++i) {
        int32_t s = star[i];
        if (s == t) continue;
        if (tri[3 * s] == b || tri[3 * s + 1] == b || tri[3 * s + 2] == b) {
          neighbor = s;
          ++count;
        }
      }
      if (count != 1 || touched[neighbor]) {
        if (last_pass) {
          remove[t] = 1;
          if (stats.degenerate_removed++ == 0) stats.degenerate_example = centroid(mesh, size_t(t));
        }
        continue;
      }
      // s with b replaced by c stays in place; s with a replaced by c is new.
      std::array<int32_t, 3> s2;
      for (int k = 0; k < 3; ++k) {
        int32_t v = tri[3 * neighbor + k];
        s2[k] = v == a ? c : v;
        if (v == b) tri[3 * neighbor + k] = c;
      }
      tri.insert(tri.end(), s2.begin(), s2.end());
      if (labels) labels->push_back((*labels)[size_t(neighbor)]);
      touched[neighbor] = 1;
      remove[t] = 1;
      ++progress;
      if (stats.collinear_repaired++ == 0) stats.collinear_example = at(mesh.points, c);
    }
    remove.resize(mesh.num_triangles(), 0);
    for (uint8_t& r : remove) r = !r;
    keep_triangles(mesh, remove, labels);
    if (progress == 0 && !last_pass) pass = 2;  // go straight to the last pass
  }
}

}  // namespace

void remove_degenerate_and_duplicates(SurfaceMesh& mesh, RepairStats& stats,
                                      std::vector<int32_t>* labels) {
  const size_t nt = mesh.num_triangles();
  auto& tri = mesh.triangles;
  if (labels && labels->size() != nt) labels = nullptr;
  // Phase 1: drop triangles with a repeated vertex.
  const std::vector<int32_t> repeated = parallel_select(nt, kGrain, [&](size_t t) {
    const int32_t a = tri[3 * t], b = tri[3 * t + 1], c = tri[3 * t + 2];
    return a == b || b == c || a == c;
  });
  if (!repeated.empty()) {
    stats.degenerate_example = centroid(mesh, size_t(repeated[0]));
    stats.degenerate_removed += repeated.size();
    std::vector<uint8_t> keep(nt, 1);
    for (int32_t t : repeated) keep[size_t(t)] = 0;
    keep_triangles(mesh, keep, labels);
  }
  // Phase 1b: flat triangles with three distinct collinear corners.
  repair_collinear_triangles(mesh, stats, labels);
  const size_t kept = mesh.num_triangles();
  // Phase 2: duplicates share their smallest vertex; bucket the triangles by
  // it (counting sort), each with its other two corners so that a bucket is
  // compared without reading the triangles again, and compare within each
  // bucket: a triangle is a duplicate when an earlier one has its corners.
  const size_t nv = mesh.num_vertices();
  auto sorted = [&](size_t t) {
    std::array<int32_t, 3> s = {tri[3 * t], tri[3 * t + 1], tri[3 * t + 2]};
    std::sort(s.begin(), s.end());
    return s;
  };
  std::vector<int32_t> offset(nv + 1, 0);
  for (size_t t = 0; t < kept; ++t)
    ++offset[std::min({tri[3 * t], tri[3 * t + 1], tri[3 * t + 2]}) + 1];
  for (size_t v = 0; v < nv; ++v) offset[v + 1] += offset[v];
  struct Entry {
    int32_t t, mid, max;  // a triangle and its corners above the bucket's vertex
  };
  std::vector<Entry> bucket(kept);
  {
    std::vector<int32_t> fill(offset.begin(), offset.end() - 1);
    for (size_t t = 0; t < kept; ++t) {
      const std::array<int32_t, 3> s = sorted(t);
      bucket[size_t(fill[s[0]]++)] = Entry{int32_t(t), s[1], s[2]};
    }
  }
  // Each triangle is in one bucket: chunks of vertices mark only their own.
  std::vector<uint8_t> duplicate(kept, 0);
  const size_t found = parallel_sum<size_t>(nv, kGrain, [&](size_t begin, size_t end) {
    size_t count = 0;
    for (size_t v = begin; v < end; ++v) {
      for (int32_t i = offset[v] + 1; i < offset[v + 1]; ++i) {
        const Entry& e = bucket[size_t(i)];
        for (int32_t j = offset[v]; j < i; ++j) {
          // Buckets are filled in triangle order: j is the earlier triangle.
          if (bucket[size_t(j)].mid == e.mid && bucket[size_t(j)].max == e.max) {
            duplicate[size_t(e.t)] = 1;
            ++count;
            break;
          }
        }
      }
    }
    return count;
  });
  if (found > 0) {
    for (size_t t = 0; t < kept; ++t) {
      if (duplicate[t] && stats.duplicates_removed++ == 0)
        stats.duplicate_example = centroid(mesh, t);
      duplicate[t] = !duplicate[t];
    }
    keep_triangles(mesh, duplicate, labels);
  }
  remove_unused_vertices(mesh, stats);
}

std::vector<int32_t> remove_triangles(SurfaceMesh& mesh, const std::vector<uint8_t>& remove,
                                      std::vector<int32_t>* labels) {
  if (labels && labels->size() != mesh.num_triangles()) labels = nullptr;
  std::vector<uint8_t> keep(mesh.num_triangles(), 1);
  for (size_t t = 0; t < keep.size() && t < remove.size(); ++t) keep[t] = !remove[t];
  keep_triangles(mesh, keep, labels);
  RepairStats unused;
  return remove_unused_vertices(mesh, unused);
}

void orient_consistently(SurfaceMesh& mesh, RepairStats& stats, TriangleAdjacency* adjacency,
                         bool adjacency_is_current) {
  const size_t nt = mesh.num_triangles();
  if (nt == 0) return;
  TriangleAdjacency adj =
      adjacency && adjacency_is_current ? std::move(*adjacency) : build_adjacency(mesh);
  auto& tri = mesh.triangles;
  // Phase 1: relative orientations across manifold edges, in memory order.
  // Two triangles agree when their shared edge runs in opposite directions.
  // The usual case, checked first on the threads: every edge agrees. Then
  // nothing flips, and the components (the keys of phase 3's volumes) come
  // from a union-find whose unions run on the threads.
  const size_t half_edges = adj.opposite.size();
  auto disagrees = [&](size_t h) {
    const int32_t o = adj.opposite[h];
    return o > int32_t(h) && half_edge_from(mesh, int32_t(h)) == half_edge_from(mesh, o);
  };
  const size_t disagreeing = parallel_sum<size_t>(half_edges, 3 * kGrain, [&](size_t b, size_t e) {
    size_t n = 0;
    for (size_t h = b; h < e; ++h) n += disagrees(h);
    return n;
  });
  std::vector<uint8_t> flip(nt, 0);
  std::vector<int32_t> root(nt);
  bool any_flipped = false;
  if (disagreeing == 0) {
    ConcurrentUnionFind components(nt);
    parallel_for(half_edges, 3 * kGrain, [&](size_t b, size_t e) {
      for (size_t h = b; h < e; ++h) {
        const int32_t o = adj.opposite[h];
        if (o > int32_t(h)) components.unite(int32_t(h / 3), o / 3);
      }
    });
    root = std::move(components).roots();
  } else {
    ParityUnionFind uf(nt);
    for (size_t h = 0; h < half_edges; ++h) {
      int32_t o = adj.opposite[h];
      if (o <= int32_t(h)) continue;  // boundary, non-manifold, or seen
      uint8_t rel = half_edge_from(mesh, int32_t(h)) == half_edge_from(mesh, o);
      if (!uf.unite(int32_t(h / 3), o / 3, rel)) stats.orientable = false;
    }
    // Phase 2: flip every triangle that disagrees with its component's root.
    for (size_t t = 0; t < nt; ++t) {
      auto [r, p] = uf.find(int32_t(t));
      root[t] = r;
      flip[t] = p;
      if (p) std::swap(tri[3 * t + 1], tri[3 * t + 2]);
      any_flipped |= p != 0;
    }
    if (any_flipped) remap_after_flips(adj, flip);
  }
  // Phase 3: outward. Signed volume per component (keyed by root), each
  // opening closed by a fan from its centroid against the loop direction.
  BoundingBox box = bounding_box(mesh.points);
  const double o[3] = {0.5 * (box.min[0] + box.max[0]), 0.5 * (box.min[1] + box.max[1]),
                       0.5 * (box.min[2] + box.max[2])};
  auto rel = [&](int32_t v, double* out) {
    for (int k = 0; k < 3; ++k) out[k] = mesh.points[3 * v + k] - o[k];
  };
  auto det = [](const double* a, const double* b, const double* c) {
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
           a[2] * (b[0] * c[1] - b[1] * c[0]);
  };
  std::vector<double> volume(nt, 0.0);  // indexed by root
  double a[3], b[3];
  auto triangle_volume = [&](size_t t) {
    double p[3], q[3], r[3];
    rel(tri[3 * t], p);
    rel(tri[3 * t + 1], q);
    rel(tri[3 * t + 2], r);
    return det(p, q, r);
  };
  // One component (all roots 0), the usual case: a sum on the threads.
  const bool one_component = parallel_sum<size_t>(nt, kGrain, [&](size_t b0, size_t e0) {
                               size_t others = 0;
                               for (size_t t = b0; t < e0; ++t) others += root[t] != 0;
                               return others;
                             }) == 0;
  if (one_component) {
    volume[0] = parallel_sum<double>(nt, kGrain, [&](size_t b0, size_t e0) {
      double sum = 0;
      for (size_t t = b0; t < e0; ++t) sum += triangle_volume(t);
      return sum;
    });
  } else {
    for (size_t t = 0; t < nt; ++t) volume[size_t(root[t])] += triangle_volume(t);
  }
  // A vertex's component: that of the last triangle of its star.
  auto vertex_root = [&](int32_t v) {
    return root[size_t(adj.star[size_t(adj.star_offsets[size_t(v) + 1] - 1)])];
  };
  for (const auto& loop : boundary_loops(mesh, adj)) {
    double cen[3] = {0, 0, 0};
    for (int32_t v : loop) {
      rel(v, a);
      for (int k = 0; k < 3; ++k) cen[k] += a[k] / double(loop.size());
    }
    double& vol = volume[size_t(vertex_root(loop[0]))];
    for (size_t i = 0; i < loop.size(); ++i) {
      rel(loop[(i + 1) % loop.size()], a);
      rel(loop[i], b);
      vol += det(cen, a, b);
    }
  }
  std::vector<uint8_t> reversed(nt, 0);
  bool any_reversed = false;
  for (size_t t = 0; t < nt; ++t) {
    if (volume[root[t]] >= 0) continue;
    std::swap(tri[3 * t + 1], tri[3 * t + 2]);
    flip[t] = !flip[t];
    reversed[t] = 1;
    any_reversed = true;
  }
  // Net count of triangles reversed relative to the input.
  for (size_t t = 0; t < nt; ++t)
    if (flip[t] && stats.flipped++ == 0) stats.flipped_example = centroid(mesh, t);
  if (adjacency) {
    if (any_reversed) remap_after_flips(adj, reversed);
    *adjacency = std::move(adj);
  }
}

}  // namespace vm
