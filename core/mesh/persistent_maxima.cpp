// Persistent maxima of a vertex field by union-find over the vertices in
// decreasing order (persistent_maxima.h).
#include "core/mesh/persistent_maxima.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace vm {

std::vector<FieldMaximum> persistent_maxima(const VertexGraph& graph, std::span<const double> field,
                                            double min_persistence) {
  const size_t nv = graph.num_vertices();
  std::vector<int32_t> order;
  order.reserve(nv);
  for (size_t v = 0; v < nv; ++v)
    if (std::isfinite(field[v])) order.push_back(int32_t(v));
  // Decreasing value; equal values by increasing index (a strict order).
  auto higher = [&](int32_t a, int32_t b) {
    return field[size_t(a)] > field[size_t(b)] || (field[size_t(a)] == field[size_t(b)] && a < b);
  };
  std::sort(order.begin(), order.end(), higher);
  std::vector<int32_t> parent(nv, -1);  // -1: not yet processed
  std::vector<int32_t> top(nv, -1);     // per root: its region's maximum
  auto find = [&](int32_t v) {
    while (parent[size_t(v)] != v) {
      parent[size_t(v)] = parent[size_t(parent[size_t(v)])];
      v = parent[size_t(v)];
    }
    return v;
  };
  std::vector<FieldMaximum> out;
  std::vector<int32_t> roots;
  for (int32_t v : order) {
    roots.clear();
    for (int32_t i = graph.offsets[size_t(v)]; i < graph.offsets[size_t(v) + 1]; ++i) {
      const int32_t w = graph.neighbors[size_t(i)];
      if (parent[size_t(w)] < 0) continue;
      const int32_t r = find(w);
      if (std::find(roots.begin(), roots.end(), r) == roots.end()) roots.push_back(r);
    }
    parent[size_t(v)] = v;
    if (roots.empty()) {
      top[size_t(v)] = v;  // a new maximum
      continue;
    }
    // The region with the highest maximum survives; the others die at v.
    int32_t keep = roots[0];
    for (int32_t r : roots)
      if (higher(top[size_t(r)], top[size_t(keep)])) keep = r;
    for (int32_t r : roots) {
      if (r == keep) continue;
      const int32_t m = top[size_t(r)];
      const double p = field[size_t(m)] - field[size_t(v)];
      if (p >= min_persistence) out.push_back({m, field[size_t(m)], p});
      parent[size_t(r)] = keep;
    }
    parent[size_t(v)] = keep;
  }
  for (int32_t v : order)
    if (parent[size_t(v)] == v && top[size_t(v)] >= 0 && find(v) == v)
      out.push_back(
          {top[size_t(v)], field[size_t(top[size_t(v)])], std::numeric_limits<double>::infinity()});
  std::sort(out.begin(), out.end(), [](const FieldMaximum& a, const FieldMaximum& b) {
    return a.persistence > b.persistence || (a.persistence == b.persistence && a.value > b.value);
  });
  return out;
}

}  // namespace vm
