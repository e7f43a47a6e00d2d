// Sharp-feature detection for remeshing (Marchandise et al., section 2.1),
// in phases: candidate edges by dihedral angle; pruning of dangling chain
// ends (a crease of a real feature closes or runs between openings, noise
// makes short open fragments); removal of short components.
#include "core/surface/sharp_features.h"

#include <cmath>
#include <numbers>

#include "core/mesh/triangle_normals.h"
#include "core/util/portable_math.h"

namespace vm {

std::vector<uint8_t> sharp_feature_edges(const SurfaceMesh& m, const TriangleAdjacency& adj,
                                         const std::vector<double>& h, double angle_degrees,
                                         double min_length_factor) {
  std::vector<uint8_t> feature(adj.opposite.size(), 0);
  if (!(angle_degrees < 180)) return feature;
  const size_t nt = m.num_triangles(), nv = m.num_vertices();
  // Phase 1: candidates, by the angle between the triangles' unit normals.
  std::vector<double> normal(3 * nt, 0.0);
  for (size_t t = 0; t < nt; ++t) {
    const Vec3 n = triangle_cross(m, t);
    const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (l > 0)
      for (int k = 0; k < 3; ++k) normal[3 * t + size_t(k)] = n[k] / l;
  }
  const double cos_limit = pm::cos(angle_degrees * std::numbers::pi / 180);
  std::vector<int> degree(nv, 0);
  std::vector<uint8_t> on_opening(nv, 0);
  for (size_t he = 0; he < adj.opposite.size(); ++he) {
    const int32_t o = adj.opposite[he];
    if (o == TriangleAdjacency::kBoundary) {
      on_opening[size_t(half_edge_from(m, int32_t(he)))] = 1;
      on_opening[size_t(half_edge_to(m, int32_t(he)))] = 1;
    }
    if (o < int32_t(he)) continue;  // boundary, non-manifold, or seen from o
    const double* n1 = &normal[3 * (he / 3)];
    const double* n2 = &normal[3 * size_t(o / 3)];
    // Degenerate triangles (zero normal) make no feature.
    const double d = n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2];
    const bool flat =
        (n1[0] == 0 && n1[1] == 0 && n1[2] == 0) || (n2[0] == 0 && n2[1] == 0 && n2[2] == 0);
    if (flat || d >= cos_limit) continue;
    feature[he] = feature[size_t(o)] = 1;
    ++degree[size_t(half_edge_from(m, int32_t(he)))];
    ++degree[size_t(half_edge_to(m, int32_t(he)))];
  }
  // Vertex -> its feature half-edges (one per undirected edge: he < o).
  std::vector<std::vector<int32_t>> at(nv);
  for (size_t he = 0; he < feature.size(); ++he)
    if (feature[he] && adj.opposite[he] > int32_t(he)) {
      at[size_t(half_edge_from(m, int32_t(he)))].push_back(int32_t(he));
      at[size_t(half_edge_to(m, int32_t(he)))].push_back(int32_t(he));
    }
  auto drop = [&](int32_t he) {
    feature[size_t(he)] = feature[size_t(adj.opposite[size_t(he)])] = 0;
    --degree[size_t(half_edge_from(m, he))];
    --degree[size_t(half_edge_to(m, he))];
  };
  // Phase 2: prune dangling ends (degree 1, not on an opening), repeatedly.
  std::vector<int32_t> queue;
  for (size_t v = 0; v < nv; ++v)
    if (degree[v] == 1 && !on_opening[v]) queue.push_back(int32_t(v));
  while (!queue.empty()) {
    const int32_t v = queue.back();
    queue.pop_back();
    if (degree[size_t(v)] != 1) continue;
    for (int32_t he : at[size_t(v)]) {
      if (!feature[size_t(he)]) continue;
      drop(he);
      const int32_t a = half_edge_from(m, he), b = half_edge_to(m, he);
      const int32_t w = a == v ? b : a;
      if (degree[size_t(w)] == 1 && !on_opening[size_t(w)]) queue.push_back(w);
      break;
    }
  }
  // Phase 3: components of the remaining edges shorter than the factor
  // times their mean size are dropped.
  std::vector<uint8_t> seen(feature.size(), 0);
  std::vector<int32_t> component, stack;
  for (size_t start = 0; start < feature.size(); ++start) {
    if (!feature[start] || seen[start] || adj.opposite[start] < int32_t(start)) continue;
    component.clear();
    stack = {int32_t(start)};
    seen[start] = 1;
    double length = 0, size_sum = 0;
    while (!stack.empty()) {
      const int32_t he = stack.back();
      stack.pop_back();
      component.push_back(he);
      const int32_t a = half_edge_from(m, he), b = half_edge_to(m, he);
      const double* pa = &m.points[3 * size_t(a)];
      const double* pb = &m.points[3 * size_t(b)];
      length += std::sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) +
                          (pa[2] - pb[2]) * (pa[2] - pb[2]));
      size_sum += 0.5 * (h[size_t(a)] + h[size_t(b)]);
      for (int32_t v : {a, b})
        for (int32_t next : at[size_t(v)])
          if (feature[size_t(next)] && !seen[size_t(next)]) {
            seen[size_t(next)] = 1;
            stack.push_back(next);
          }
    }
    const double mean_size = size_sum / double(component.size());
    if (length < min_length_factor * mean_size)
      for (int32_t he : component) drop(he);
  }
  return feature;
}

}  // namespace vm
