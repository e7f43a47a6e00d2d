// Surface topology: components (union-find over shared vertices), edges and
// boundary loops (adjacency.h, boundary_loops.h), bow-tie vertices (more
// than one triangle fan in a vertex star), Euler characteristic and genus
// from chi = 2 - 2 g - b per component.
#include "core/mesh/topology.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"
#include "core/util/concurrent_union_find.h"
#include "core/util/parallel.h"

namespace vm {
namespace {

/// Chunk of the loops over vertices, triangles or half-edges (parallel.h).
constexpr size_t kGrain = size_t(1) << 16;

// Whether the triangles around v form a single fan: walking from one of them
// across the manifold edges incident to v, both ways, reaches all of them.
bool single_fan(const SurfaceMesh& m, const TriangleAdjacency& adj, int32_t v) {
  const int32_t b = adj.star_offsets[v], d = adj.star_offsets[v + 1] - b;
  const int32_t t0 = adj.star[b];
  int32_t reached = 1;
  int32_t first = other_half_edge_at(m, t0, v, -1);
  for (int32_t start : {first, other_half_edge_at(m, t0, v, first)}) {
    int32_t h = start;
    for (int32_t steps = 0; steps < d; ++steps) {
      int32_t o = adj.opposite[h];
      if (o < 0) break;                      // boundary or non-manifold edge: the fan ends
      if (o / 3 == t0) return reached == d;  // closed around v
      ++reached;
      h = other_half_edge_at(m, o / 3, v, o);
    }
  }
  return reached == d;
}

// single_fan for a star of at most kSmallStar triangles, the same walk on
// each triangle's two half-edges at v and their opposites gathered first:
// those loads are independent, where the walk waits on each step.
constexpr int32_t kSmallStar = 16;
bool single_small_fan(const SurfaceMesh& m, const TriangleAdjacency& adj, int32_t v) {
  const int32_t b = adj.star_offsets[v], d = adj.star_offsets[v + 1] - b;
  int32_t tri[kSmallStar], he[kSmallStar][2], op[kSmallStar][2];
  for (int32_t i = 0; i < d; ++i) {
    const int32_t t = adj.star[size_t(b + i)];
    const int32_t* c = &m.triangles[3 * size_t(t)];
    if ((c[0] == v) + (c[1] == v) + (c[2] == v) != 1) return single_fan(m, adj, v);  // degenerate
    const int32_t k = c[0] == v ? 0 : c[1] == v ? 1 : 2;
    // The half-edge from v and the one to v, in index order (as
    // other_half_edge_at finds them).
    const int32_t out = 3 * t + k, in = 3 * t + (k + 2) % 3;
    tri[i] = t;
    he[i][0] = std::min(out, in);
    he[i][1] = std::max(out, in);
    op[i][0] = adj.opposite[size_t(he[i][0])];
    op[i][1] = adj.opposite[size_t(he[i][1])];
  }
  int32_t reached = 1;
  for (int first = 0; first < 2; ++first) {
    int32_t o = op[0][first];
    for (int32_t steps = 0; steps < d; ++steps) {
      if (o < 0) break;  // boundary or non-manifold edge: the fan ends
      const int32_t t = o / 3;
      if (t == tri[0]) return reached == d;  // closed around v
      ++reached;
      int32_t j = 1;
      while (j < d && tri[j] != t) ++j;
      if (j == d) return single_fan(m, adj, v);  // not in the star: cannot be
      o = op[j][he[j][0] == o ? 1 : 0];
    }
  }
  return reached == d;
}

}  // namespace

Opening describe_loop(const SurfaceMesh& m, std::vector<int32_t> loop) {
  Opening op;
  const size_t n = loop.size();
  auto p = [&](size_t i) { return &m.points[3 * loop[i % n]]; };
  double wsum = 0;
  for (size_t i = 0; i < n; ++i) {
    const double *a = p(i), *b = p(i + 1);
    double len = std::sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
                           (b[2] - a[2]) * (b[2] - a[2]));
    op.perimeter += len;
    for (int k = 0; k < 3; ++k) op.centroid[k] += len * 0.5 * (a[k] + b[k]);
    wsum += len;
  }
  if (wsum > 0)
    for (int k = 0; k < 3; ++k) op.centroid[k] /= wsum;
  double area[3] = {0, 0, 0};
  for (size_t i = 0; i < n; ++i) {
    double u[3], w[3];
    for (int k = 0; k < 3; ++k) {
      u[k] = p(i)[k] - op.centroid[k];
      w[k] = p(i + 1)[k] - op.centroid[k];
    }
    area[0] += 0.5 * (u[1] * w[2] - u[2] * w[1]);
    area[1] += 0.5 * (u[2] * w[0] - u[0] * w[2]);
    area[2] += 0.5 * (u[0] * w[1] - u[1] * w[0]);
  }
  double amag = std::sqrt(area[0] * area[0] + area[1] * area[1] + area[2] * area[2]);
  op.radius = std::sqrt(amag / std::numbers::pi);
  // The loop follows its triangles' half-edges; the cap faces the other way,
  // i.e. outward for an outward-oriented surface.
  if (amag > 0)
    for (int k = 0; k < 3; ++k) op.normal[k] = -area[k] / amag;
  op.loop = std::move(loop);
  return op;
}

TopologyReport analyze_topology(const SurfaceMesh& mesh) {
  return analyze_topology(mesh, build_adjacency(mesh));
}

TopologyReport analyze_topology(const SurfaceMesh& mesh, const TriangleAdjacency& adj) {
  TopologyReport r;
  const size_t nv = mesh.num_vertices(), nt = mesh.num_triangles();
  r.vertices = nv;
  r.triangles = nt;
  if (nt == 0) return r;
  const auto& tri = mesh.triangles;
  r.edges = adj.num_edges;
  r.nonmanifold_edges = adj.num_nonmanifold_edges;
  if (!adj.nonmanifold_example.empty()) {
    for (int k = 0; k < 3; ++k)
      r.nonmanifold_edge_example[k] = 0.5 * (mesh.points[3 * adj.nonmanifold_example[0] + k] +
                                             mesh.points[3 * adj.nonmanifold_example[1] + k]);
  }
  // Boundary half-edges, and the edges as the Euler characteristic counts
  // them: each manifold edge from its half-edge with the smaller index, each
  // boundary edge once.
  struct EdgeCounts {
    size_t boundary = 0, euler = 0;
    EdgeCounts& operator+=(const EdgeCounts& o) {
      boundary += o.boundary;
      euler += o.euler;
      return *this;
    }
  };
  const EdgeCounts edge_counts =
      parallel_sum<EdgeCounts>(adj.opposite.size(), kGrain, [&](size_t b, size_t e) {
        EdgeCounts n;
        for (size_t h = b; h < e; ++h) {
          const int32_t o = adj.opposite[h];
          n.boundary += o == TriangleAdjacency::kBoundary;
          n.euler += o == TriangleAdjacency::kBoundary || o > int32_t(h);
        }
        return n;
      });
  r.boundary_edges = edge_counts.boundary;

  // Components over shared vertices, numbered by decreasing size. Each set
  // is rooted at its smallest vertex.
  std::vector<int32_t> parent;
  {
    ConcurrentUnionFind uf(nv);
    parallel_for(nt, kGrain, [&](size_t b, size_t e) {
      for (size_t t = b; t < e; ++t) {
        uf.unite(tri[3 * t], tri[3 * t + 1]);
        uf.unite(tri[3 * t], tri[3 * t + 2]);
      }
    });
    parent = std::move(uf).roots();
  }
  std::vector<int32_t> root_id(nv, -1);
  std::vector<size_t> sizes;
  for (size_t t = 0; t < nt; ++t) {
    const int32_t root = parent[size_t(tri[3 * t])];
    if (root_id[root] < 0) {
      root_id[root] = int32_t(sizes.size());
      sizes.push_back(0);
    }
    ++sizes[root_id[root]];
  }
  std::vector<int32_t> order(sizes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int32_t a, int32_t b) { return sizes[a] > sizes[b]; });
  std::vector<int32_t> rank(sizes.size());
  for (size_t i = 0; i < order.size(); ++i) rank[order[i]] = int32_t(i);
  r.components = int(sizes.size());
  r.component_triangles.resize(sizes.size());
  for (size_t i = 0; i < order.size(); ++i) r.component_triangles[i] = sizes[order[i]];
  r.triangle_component.resize(nt);
  parallel_for(nt, kGrain, [&](size_t b, size_t e) {
    for (size_t t = b; t < e; ++t)
      r.triangle_component[t] = rank[size_t(root_id[size_t(parent[size_t(tri[3 * t])])])];
  });

  // Bow-tie vertices, and the vertices in use.
  struct VertexCounts {
    size_t bow_ties = 0, used = 0;
    VertexCounts& operator+=(const VertexCounts& o) {
      bow_ties += o.bow_ties;
      used += o.used;
      return *this;
    }
  };
  const VertexCounts vc = parallel_sum<VertexCounts>(nv, kGrain, [&](size_t b, size_t e) {
    VertexCounts c;
    for (size_t v = b; v < e; ++v) {
      const int32_t d = adj.star_offsets[v + 1] - adj.star_offsets[v];
      if (d == 0) continue;
      ++c.used;
      if (!(d <= kSmallStar ? single_small_fan(mesh, adj, int32_t(v))
                            : single_fan(mesh, adj, int32_t(v))))
        ++c.bow_ties;
    }
    return c;
  });
  r.nonmanifold_vertices = vc.bow_ties;

  // Openings, largest first.
  for (auto& loop : boundary_loops(mesh, adj))
    (loop.size() < 3 ? r.slits : r.openings).push_back(describe_loop(mesh, std::move(loop)));
  std::stable_sort(r.openings.begin(), r.openings.end(),
                   [](const Opening& a, const Opening& b) { return a.radius > b.radius; });
  r.closed = r.boundary_edges == 0;

  // Euler characteristic and genus, per component.
  r.euler_characteristic = long(nv) - long(r.edges) + long(nt);
  if (r.nonmanifold_edges == 0 && r.nonmanifold_vertices == 0 && r.components == 1) {
    // One component: its used vertices, all edges, all triangles.
    const long chi = long(vc.used) - long(edge_counts.euler) + long(nt);
    r.genus = int((2 - chi - long(r.openings.size() + r.slits.size())) / 2);
  } else if (r.nonmanifold_edges == 0 && r.nonmanifold_vertices == 0) {
    const int nc = r.components;
    std::vector<long> chi(nc, 0), loops(nc, 0);
    std::vector<int32_t> vcomp(nv, -1);
    for (size_t t = 0; t < nt; ++t) {
      int c = r.triangle_component[t];
      chi[c] += 1;  // F
      for (int k = 0; k < 3; ++k) vcomp[tri[3 * t + k]] = c;
      for (int k = 0; k < 3; ++k) {
        // E: each manifold edge counted from its half-edge with the smaller
        // index, each boundary edge once.
        int32_t h = int32_t(3 * t + k), o = adj.opposite[h];
        if (o == TriangleAdjacency::kBoundary || o > h) chi[c] -= 1;
      }
    }
    for (size_t v = 0; v < nv; ++v)
      if (vcomp[v] >= 0) chi[vcomp[v]] += 1;  // V
    for (const Opening& op : r.openings) loops[vcomp[op.loop[0]]] += 1;
    for (const Opening& op : r.slits) loops[vcomp[op.loop[0]]] += 1;
    long genus = 0;
    for (int c = 0; c < nc; ++c) genus += (2 - chi[c] - loops[c]) / 2;
    r.genus = int(genus);
  }
  return r;
}

SurfaceMesh extract_component(const SurfaceMesh& mesh, const TopologyReport& report,
                              int component) {
  SurfaceMesh out;
  std::vector<int32_t> remap(mesh.num_vertices(), -1);
  for (size_t t = 0; t < mesh.num_triangles(); ++t) {
    if (report.triangle_component[t] != component) continue;
    for (int k = 0; k < 3; ++k) {
      int32_t v = mesh.triangles[3 * t + k];
      if (remap[v] < 0) {
        remap[v] = int32_t(out.num_vertices());
        for (int q = 0; q < 3; ++q) out.points.push_back(mesh.points[3 * v + q]);
      }
      out.triangles.push_back(remap[v]);
    }
  }
  return out;
}

}  // namespace vm
