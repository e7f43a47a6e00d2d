// Safe surface repairs. Orientation follows the usual breadth-first
// propagation across manifold edges (each shared edge must be traversed in
// opposite directions), then each component is turned outward by the sign of
// its enclosed volume, openings closed by fans to their centroids.
#include "core/mesh/repair.h"

#include <algorithm>
#include <array>

#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"

namespace vm {
namespace {

bool zero_area(const SurfaceMesh& m, size_t t) {
  const double* a = &m.points[3 * m.triangles[3 * t]];
  const double* b = &m.points[3 * m.triangles[3 * t + 1]];
  const double* c = &m.points[3 * m.triangles[3 * t + 2]];
  double u[3], v[3];
  for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], v[k] = c[k] - a[k];
  return u[1] * v[2] - u[2] * v[1] == 0 && u[2] * v[0] - u[0] * v[2] == 0 &&
         u[0] * v[1] - u[1] * v[0] == 0;
}

void remove_unused_vertices(SurfaceMesh& mesh, RepairStats& stats) {
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
  mesh.points.resize(3 * size_t(next));
  for (int32_t& v : mesh.triangles) v = remap[v];
}

// Signed volume enclosed by the triangles of one component, each boundary
// loop closed by a fan from its centroid (the cap's sign follows the loop
// direction, which follows the triangles).
double closed_signed_volume(const SurfaceMesh& m,
                            const std::vector<int32_t>& tris,
                            const std::vector<std::vector<int32_t>>& loops) {
  auto vol = [](const double* a, const double* b, const double* c) {
    return (a[0] * (b[1] * c[2] - b[2] * c[1]) -
            a[1] * (b[0] * c[2] - b[2] * c[0]) +
            a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
  };
  // Translate to the first point to limit cancellation.
  const double* o = &m.points[3 * m.triangles[3 * tris[0]]];
  auto rel = [&](int32_t v, double* out) {
    for (int k = 0; k < 3; ++k) out[k] = m.points[3 * v + k] - o[k];
  };
  double total = 0, a[3], b[3], c[3];
  for (int32_t t : tris) {
    rel(m.triangles[3 * t], a);
    rel(m.triangles[3 * t + 1], b);
    rel(m.triangles[3 * t + 2], c);
    total += vol(a, b, c);
  }
  for (const auto& loop : loops) {
    double cen[3] = {0, 0, 0};
    for (int32_t v : loop) {
      rel(v, a);
      for (int k = 0; k < 3; ++k) cen[k] += a[k] / double(loop.size());
    }
    // The cap runs against the loop direction.
    for (size_t i = 0; i < loop.size(); ++i) {
      rel(loop[(i + 1) % loop.size()], a);
      rel(loop[i], b);
      total += vol(cen, a, b);
    }
  }
  return total;
}

// Removes each triangle t = (a, b, c) whose corners are distinct but
// collinear (c strictly inside the longest edge a-b) by splitting its
// neighbor s across a-b at c into two triangles with s's orientation, which
// keeps the surface closed: dropping t alone would open a slit. A few passes
// handle chains; flat triangles left then (no single neighbor across the
// long edge, or a flat neighbor) are dropped and counted as degenerate.
void repair_collinear_triangles(SurfaceMesh& mesh, RepairStats& stats) {
  auto& tri = mesh.triangles;
  for (int pass = 0; pass < 4; ++pass) {
    std::vector<int32_t> flat;
    for (size_t t = 0; t < mesh.num_triangles(); ++t)
      if (zero_area(mesh, t)) flat.push_back(int32_t(t));
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
          ++stats.degenerate_removed;
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
      touched[neighbor] = 1;
      remove[t] = 1;
      ++progress;
      ++stats.collinear_repaired;
    }
    remove.resize(mesh.num_triangles(), 0);
    size_t out = 0;
    for (size_t t = 0; t < mesh.num_triangles(); ++t) {
      if (remove[t]) continue;
      for (int k = 0; k < 3; ++k) tri[3 * out + k] = tri[3 * t + k];
      ++out;
    }
    tri.resize(3 * out);
    if (progress == 0 && !last_pass) pass = 2;  // go straight to the last pass
  }
}

}  // namespace

void remove_degenerate_and_duplicates(SurfaceMesh& mesh, RepairStats& stats) {
  const size_t nt = mesh.num_triangles();
  auto& tri = mesh.triangles;
  // Phase 1: drop triangles with a repeated vertex, compacting in place.
  size_t kept = 0;
  for (size_t t = 0; t < nt; ++t) {
    int32_t a = tri[3 * t], b = tri[3 * t + 1], c = tri[3 * t + 2];
    if (a == b || b == c || a == c) {
      ++stats.degenerate_removed;
      continue;
    }
    tri[3 * kept] = a, tri[3 * kept + 1] = b, tri[3 * kept + 2] = c;
    ++kept;
  }
  tri.resize(3 * kept);
  // Phase 1b: flat triangles with three distinct collinear corners.
  repair_collinear_triangles(mesh, stats);
  kept = mesh.num_triangles();
  // Phase 2: duplicates share their smallest vertex; bucket the triangles by
  // it (counting sort) and compare within each bucket.
  const size_t nv = mesh.num_vertices();
  std::vector<int32_t> offset(nv + 1, 0);
  auto min_vertex = [&](size_t t) {
    return std::min({tri[3 * t], tri[3 * t + 1], tri[3 * t + 2]});
  };
  for (size_t t = 0; t < kept; ++t) ++offset[min_vertex(t) + 1];
  for (size_t v = 0; v < nv; ++v) offset[v + 1] += offset[v];
  std::vector<int32_t> bucket(kept);
  {
    std::vector<int32_t> fill(offset.begin(), offset.end() - 1);
    for (size_t t = 0; t < kept; ++t) bucket[fill[min_vertex(t)]++] = int32_t(t);
  }
  auto sorted = [&](int32_t t) {
    std::array<int32_t, 3> s = {tri[3 * t], tri[3 * t + 1], tri[3 * t + 2]};
    std::sort(s.begin(), s.end());
    return s;
  };
  std::vector<uint8_t> duplicate(kept, 0);
  for (size_t v = 0; v < nv; ++v) {
    for (int32_t i = offset[v]; i < offset[v + 1]; ++i) {
      auto si = sorted(bucket[i]);
      for (int32_t j = offset[v]; j < i; ++j) {
        // Buckets are filled in triangle order: j is the earlier triangle.
        if (!duplicate[bucket[j]] && sorted(bucket[j]) == si) {
          duplicate[bucket[i]] = 1;
          break;
        }
      }
    }
  }
  size_t out = 0;
  for (size_t t = 0; t < kept; ++t) {
    if (duplicate[t]) {
      ++stats.duplicates_removed;
      continue;
    }
    for (int k = 0; k < 3; ++k) tri[3 * out + k] = tri[3 * t + k];
    ++out;
  }
  tri.resize(3 * out);
  remove_unused_vertices(mesh, stats);
}

void orient_consistently(SurfaceMesh& mesh, RepairStats& stats,
                         TriangleAdjacency* adjacency) {
  const size_t nt = mesh.num_triangles();
  if (nt == 0) return;
  TriangleAdjacency adj = build_adjacency(mesh);
  auto& tri = mesh.triangles;
  std::vector<int32_t> component(nt, -1);
  std::vector<uint8_t> flip(nt, 0);
  std::vector<std::vector<int32_t>> comp_tris;
  std::vector<int32_t> queue;
  for (size_t seed = 0; seed < nt; ++seed) {
    if (component[seed] >= 0) continue;
    int32_t cid = int32_t(comp_tris.size());
    comp_tris.emplace_back();
    component[seed] = cid;
    queue.assign(1, int32_t(seed));
    while (!queue.empty()) {
      int32_t t = queue.back();
      queue.pop_back();
      comp_tris[cid].push_back(t);
      for (int k = 0; k < 3; ++k) {
        int32_t o = adj.opposite[3 * t + k];
        if (o < 0) continue;
        int32_t s = o / 3;
        // Consistent iff the two half-edges run in opposite directions,
        // taking the flips decided so far into account.
        bool same_dir = half_edge_from(mesh, 3 * t + k) == half_edge_from(mesh, o);
        bool need_flip = same_dir != bool(flip[t]);
        if (component[s] < 0) {
          component[s] = cid;
          flip[s] = need_flip;
          queue.push_back(s);
        } else if (bool(flip[s]) != need_flip) {
          stats.orientable = false;
        }
      }
    }
  }
  for (size_t t = 0; t < nt; ++t)
    if (flip[t]) std::swap(tri[3 * t + 1], tri[3 * t + 2]);
  remap_after_flips(adj, flip);
  // Outward: per component, positive enclosed volume.
  std::vector<std::vector<std::vector<int32_t>>> comp_loops(comp_tris.size());
  std::vector<int32_t> vertex_comp(mesh.num_vertices(), -1);
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) vertex_comp[tri[3 * t + k]] = component[t];
  for (auto& loop : boundary_loops(mesh, adj))
    comp_loops[vertex_comp[loop[0]]].push_back(std::move(loop));
  std::vector<uint8_t> reversed(nt, 0);
  for (size_t c = 0; c < comp_tris.size(); ++c) {
    if (closed_signed_volume(mesh, comp_tris[c], comp_loops[c]) >= 0) continue;
    for (int32_t t : comp_tris[c]) {
      std::swap(tri[3 * t + 1], tri[3 * t + 2]);
      flip[t] = !flip[t];
      reversed[t] = 1;
    }
  }
  if (adjacency) {
    remap_after_flips(adj, reversed);
    *adjacency = std::move(adj);
  }
  // Net count of triangles reversed relative to the input.
  for (uint8_t f : flip) stats.flipped += f;
}

}  // namespace vm
