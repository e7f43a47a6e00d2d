// Approximate geodesic distances on a triangle surface: shortest paths along
// its edges (Dijkstra's algorithm over the vertex graph). Paths along edges
// overestimate the true geodesic distance by a few percent on irregular
// meshes (up to ~8% on a regular grid), which is enough to find extremities
// and to follow a vessel from its tip.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm {

/// The vertex graph of a surface in CSR form: the neighbors of vertex v are
/// neighbors[offsets[v] .. offsets[v + 1]) with the edge lengths (model units)
/// in `lengths` at the same positions. Each undirected edge appears in both
/// directions.
struct VertexGraph {
  std::vector<int32_t> offsets;  ///< num_vertices + 1
  std::vector<int32_t> neighbors;
  std::vector<double> lengths;
  size_t num_vertices() const { return offsets.empty() ? 0 : offsets.size() - 1; }
};

/// Builds the vertex graph of `mesh` (edges of its triangles, each once per
/// direction). O(n log n).
VertexGraph build_vertex_graph(const SurfaceMesh& mesh);

/// A resumable Dijkstra search from a set of source vertices: settle_until(L)
/// settles, in increasing distance, every vertex whose distance is <= L, so
/// that a search can be grown as far as a caller needs. The distance array
/// has one entry per graph vertex: final for settled vertices, a tentative
/// value or infinity for the others.
class EdgeDijkstra {
 public:
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();

  /// Starts from `sources` (distance 0). `graph` must outlive the search.
  EdgeDijkstra(const VertexGraph& graph, std::span<const int32_t> sources);

  /// Settles the vertices at distance <= limit; returns the number settled
  /// so far.
  size_t settle_until(double limit);
  /// Settles every vertex reachable from the sources.
  void settle_all() { settle_until(kInfinity); }

  /// Per vertex: its distance (final once settled).
  const std::vector<double>& distances() const { return dist_; }
  /// The settled vertices, in order of increasing distance.
  const std::vector<int32_t>& settled() const { return settled_; }
  /// Whether vertex v is settled.
  bool is_settled(int32_t v) const { return done_[size_t(v)] != 0; }
  /// The largest settled distance (0 before any vertex is settled).
  double reach() const { return settled_.empty() ? 0 : dist_[size_t(settled_.back())]; }

 private:
  const VertexGraph& graph_;
  std::vector<double> dist_;
  std::vector<uint8_t> done_;
  std::vector<int32_t> settled_;
  std::vector<std::pair<double, int32_t>> heap_;  ///< min-heap on distance
};

}  // namespace vm
