// Shortest paths along the edges of a surface (edge_geodesics.h).
#include "core/mesh/edge_geodesics.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/util/portable_math.h"

namespace vm {

VertexGraph build_vertex_graph(const SurfaceMesh& mesh) {
  const size_t nv = mesh.num_vertices();
  std::vector<std::pair<int32_t, int32_t>> directed;
  directed.reserve(2 * mesh.triangles.size());
  for (size_t t = 0; t < mesh.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = mesh.triangles[3 * t + size_t(k)];
      const int32_t b = mesh.triangles[3 * t + size_t((k + 1) % 3)];
      directed.emplace_back(a, b);
      directed.emplace_back(b, a);
    }
  std::sort(directed.begin(), directed.end());
  directed.erase(std::unique(directed.begin(), directed.end()), directed.end());
  VertexGraph g;
  g.offsets.assign(nv + 1, 0);
  g.neighbors.reserve(directed.size());
  g.lengths.reserve(directed.size());
  for (const auto& [a, b] : directed) {
    ++g.offsets[size_t(a) + 1];
    g.neighbors.push_back(b);
    const double* p = &mesh.points[3 * size_t(a)];
    const double* q = &mesh.points[3 * size_t(b)];
    g.lengths.push_back(pm::hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]));
  }
  for (size_t v = 0; v < nv; ++v) g.offsets[v + 1] += g.offsets[v];
  return g;
}

EdgeDijkstra::EdgeDijkstra(const VertexGraph& graph, std::span<const int32_t> sources)
    : graph_(graph), dist_(graph.num_vertices(), kInfinity), done_(graph.num_vertices(), 0) {
  for (int32_t s : sources) {
    if (s < 0 || size_t(s) >= dist_.size() || dist_[size_t(s)] == 0) continue;
    dist_[size_t(s)] = 0;
    heap_.emplace_back(0.0, s);
  }
  std::make_heap(heap_.begin(), heap_.end(), std::greater<>());
}

size_t EdgeDijkstra::settle_until(double limit) {
  while (!heap_.empty() && heap_.front().first <= limit) {
    std::pop_heap(heap_.begin(), heap_.end(), std::greater<>());
    const auto [d, v] = heap_.back();
    heap_.pop_back();
    if (done_[size_t(v)] || d > dist_[size_t(v)]) continue;
    done_[size_t(v)] = 1;
    settled_.push_back(v);
    for (int32_t i = graph_.offsets[size_t(v)]; i < graph_.offsets[size_t(v) + 1]; ++i) {
      const int32_t w = graph_.neighbors[size_t(i)];
      const double dw = d + graph_.lengths[size_t(i)];
      if (!done_[size_t(w)] && dw < dist_[size_t(w)]) {
        dist_[size_t(w)] = dw;
        heap_.emplace_back(dw, w);
        std::push_heap(heap_.begin(), heap_.end(), std::greater<>());
      }
    }
  }
  return settled_.size();
}

}  // namespace vm
