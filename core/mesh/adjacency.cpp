#include "core/mesh/adjacency.h"

#include <algorithm>

namespace vm {

TriangleAdjacency build_vertex_stars(const SurfaceMesh& mesh) {
  TriangleAdjacency adj;
  const size_t nv = mesh.num_vertices();
  const size_t nt = mesh.num_triangles();
  const auto& tri = mesh.triangles;
  adj.star_offsets.assign(nv + 1, 0);
  for (int32_t v : tri) ++adj.star_offsets[v + 1];
  for (size_t v = 0; v < nv; ++v) adj.star_offsets[v + 1] += adj.star_offsets[v];
  adj.star.resize(tri.size());
  std::vector<int32_t> fill(adj.star_offsets.begin(), adj.star_offsets.end() - 1);
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) adj.star[fill[tri[3 * t + k]]++] = int32_t(t);
  return adj;
}

TriangleAdjacency build_adjacency(const SurfaceMesh& mesh) {
  const auto& tri = mesh.triangles;
  // Phase 1: vertex stars by counting sort.
  TriangleAdjacency adj = build_vertex_stars(mesh);

  // Phase 2: each edge once, from the first half-edge that meets it: the
  // triangles of the star of its smaller vertex that contain the other one.
  constexpr int32_t kUnset = -3;
  adj.opposite.assign(tri.size(), kUnset);
  std::vector<int32_t> sharing;  // half-edges on the current edge
  for (size_t h0 = 0; h0 < tri.size(); ++h0) {
    if (adj.opposite[h0] != kUnset) continue;
    const int32_t t = int32_t(h0 / 3);
    const int32_t a = tri[h0], b = half_edge_to(mesh, int32_t(h0));
    const int32_t lo = std::min(a, b), hi = std::max(a, b);
    sharing.assign(1, int32_t(h0));
    for (int32_t i = adj.star_offsets[lo]; i < adj.star_offsets[lo + 1]; ++i) {
      int32_t s = adj.star[i];
      if (s == t) continue;
      int32_t ilo = -1, ihi = -1;
      for (int q = 0; q < 3; ++q) {
        if (tri[3 * s + q] == lo) ilo = q;
        if (tri[3 * s + q] == hi) ihi = q;
      }
      if (ihi < 0) continue;
      // The half-edge of s on {lo, hi} starts at whichever precedes the other.
      sharing.push_back((ilo + 1) % 3 == ihi ? 3 * s + ilo : 3 * s + ihi);
    }
    ++adj.num_edges;
    if (sharing.size() == 1) {
      adj.opposite[h0] = TriangleAdjacency::kBoundary;
    } else if (sharing.size() == 2) {
      adj.opposite[sharing[0]] = sharing[1];
      adj.opposite[sharing[1]] = sharing[0];
    } else {
      for (int32_t h : sharing) adj.opposite[h] = TriangleAdjacency::kNonManifold;
      if (adj.num_nonmanifold_edges == 0) adj.nonmanifold_example = {a, b};
      ++adj.num_nonmanifold_edges;
    }
  }
  return adj;
}

void remap_after_flips(TriangleAdjacency& adj, const std::vector<uint8_t>& flipped) {
  // Reversing (v0, v1, v2) to (v0, v2, v1) maps its half-edges 0, 1, 2 to
  // 2, 1, 0 (each now runs the other way).
  auto map = [&](int32_t h) {
    int32_t t = h / 3, k = h % 3;
    return flipped[t] ? 3 * t + (2 - k) : h;
  };
  std::vector<int32_t> old = std::move(adj.opposite);
  adj.opposite.assign(old.size(), TriangleAdjacency::kBoundary);
  for (size_t h = 0; h < old.size(); ++h)
    adj.opposite[map(int32_t(h))] = old[h] >= 0 ? map(old[h]) : old[h];
}

}  // namespace vm
