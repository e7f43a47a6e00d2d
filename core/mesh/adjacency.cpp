#include "core/mesh/adjacency.h"

#include <algorithm>
#include <string>

#include "core/util/parallel.h"

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
  const size_t nv = mesh.num_vertices();
  // Phase 1: vertex stars by counting sort.
  TriangleAdjacency adj = build_vertex_stars(mesh);

  // Phase 2: each edge once, at its smaller vertex lo: the half-edges of the
  // star of lo whose other end is larger, grouped by that end (one star
  // read per vertex). Chunks of vertices run on the threads: an edge's
  // half-edges are written by the chunk of its lo only.
  adj.opposite.assign(tri.size(), TriangleAdjacency::kBoundary);
  struct Spoke {
    int32_t hi, h;  // the other end, the half-edge
  };
  struct Counts {
    size_t edges = 0, nonmanifold = 0;
    // The smallest half-edge of a non-manifold edge: the example is the
    // first such edge in half-edge order.
    int32_t first_nonmanifold = -1;
  };
  constexpr size_t kGrain = size_t(1) << 15;
  std::vector<Counts> counts((nv + kGrain - 1) / kGrain);
  parallel_for(nv, kGrain, [&](size_t begin, size_t end) {
    Counts& c = counts[begin / kGrain];
    std::vector<Spoke> spokes;
    for (size_t lo = begin; lo < end; ++lo) {
      spokes.clear();
      for (int32_t i = adj.star_offsets[lo]; i < adj.star_offsets[lo + 1]; ++i) {
        const int32_t t3 = 3 * adj.star[size_t(i)];
        for (int q = 0; q < 3; ++q) {
          if (tri[size_t(t3 + q)] != int32_t(lo)) continue;
          const int32_t out = t3 + q, in = t3 + (q + 2) % 3;  // from lo, to lo
          const int32_t to = tri[size_t(t3 + (q + 1) % 3)], from = tri[size_t(in)];
          if (to > int32_t(lo)) spokes.push_back({to, out});
          if (from > int32_t(lo)) spokes.push_back({from, in});
        }
      }
      // Group by the other end (insertion sort: a star has a few spokes).
      for (size_t i = 1; i < spokes.size(); ++i)
        for (size_t j = i; j > 0 && spokes[j - 1].hi > spokes[j].hi; --j)
          std::swap(spokes[j - 1], spokes[j]);
      for (size_t i = 0; i < spokes.size();) {
        size_t j = i + 1;
        while (j < spokes.size() && spokes[j].hi == spokes[i].hi) ++j;
        ++c.edges;
        if (j - i == 2) {
          adj.opposite[size_t(spokes[i].h)] = spokes[i + 1].h;
          adj.opposite[size_t(spokes[i + 1].h)] = spokes[i].h;
        } else if (j - i > 2) {
          for (size_t k = i; k < j; ++k) {
            const int32_t h = spokes[k].h;
            adj.opposite[size_t(h)] = TriangleAdjacency::kNonManifold;
            if (c.first_nonmanifold < 0 || h < c.first_nonmanifold) c.first_nonmanifold = h;
          }
          ++c.nonmanifold;
        }
        i = j;
      }
    }
  });
  int32_t first_nonmanifold = -1;
  for (const Counts& c : counts) {
    adj.num_edges += c.edges;
    adj.num_nonmanifold_edges += c.nonmanifold;
    if (c.first_nonmanifold >= 0 &&
        (first_nonmanifold < 0 || c.first_nonmanifold < first_nonmanifold))
      first_nonmanifold = c.first_nonmanifold;
  }
  if (first_nonmanifold >= 0)
    adj.nonmanifold_example = {tri[size_t(first_nonmanifold)],
                               half_edge_to(mesh, first_nonmanifold)};
  return adj;
}

void remap_after_flips(TriangleAdjacency& adj, const std::vector<uint8_t>& flipped) {
  // Reversing (v0, v1, v2) to (v0, v2, v1) maps its half-edges 0, 1, 2 to
  // 2, 1, 0 (each now runs the other way).
  auto map = [&](int32_t h) {
    int32_t t = h / 3, k = h % 3;
    return flipped[t] ? 3 * t + (2 - k) : h;
  };
  // In place: the entries of each flipped triangle move (0 and 2 trade),
  // then every opposite half-edge is mapped.
  std::vector<int32_t>& opposite = adj.opposite;
  for (size_t t = 0; t < flipped.size(); ++t)
    if (flipped[t]) std::swap(opposite[3 * t], opposite[3 * t + 2]);
  for (int32_t& o : opposite)
    if (o >= 0) o = map(o);
}

VertexRings vertex_rings(const SurfaceMesh& m, const TriangleAdjacency& adj) {
  const size_t nv = m.num_vertices();
  VertexRings r;
  r.offsets.assign(nv + 1, 0);
  std::vector<int32_t> scratch;
  for (size_t v = 0; v < nv; ++v) {
    scratch.clear();
    for (int32_t i = adj.star_offsets[v]; i < adj.star_offsets[v + 1]; ++i) {
      const int32_t* t = &m.triangles[3 * size_t(adj.star[size_t(i)])];
      for (int k = 0; k < 3; ++k)
        if (size_t(t[k]) != v) {
          bool seen = false;
          for (int32_t u : scratch) seen = seen || u == t[k];
          if (!seen) scratch.push_back(t[k]);
        }
    }
    r.ids.insert(r.ids.end(), scratch.begin(), scratch.end());
    r.offsets[v + 1] = int32_t(r.ids.size());
  }
  return r;
}

Status check_manifold_oriented(const SurfaceMesh& wall, const TriangleAdjacency& adj) {
  if (adj.num_nonmanifold_edges > 0)
    return Status::Error("the wall has " + std::to_string(adj.num_nonmanifold_edges) +
                         " non-manifold edges");
  for (size_t h = 0; h < adj.opposite.size(); ++h) {
    const int32_t o = adj.opposite[h];
    if (o >= 0 && half_edge_from(wall, int32_t(h)) != half_edge_to(wall, o))
      return Status::Error("the wall is not consistently oriented");
  }
  return Status::Ok();
}

}  // namespace vm
