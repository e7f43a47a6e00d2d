// Requested layer thickness and graded reduction (see layer_thickness.h;
// Marchandise et al., section 2.2).
#include "core/layers/layer_thickness.h"

#include <cmath>
#include <queue>
#include <utility>

namespace vm {
using namespace layers;  // NOLINT: the layer stage's own vector helpers

Result<std::vector<double>> requested_thickness(const LayerSpec& spec,
                                                const std::vector<double>& radius, size_t nv) {
  using R = Result<std::vector<double>>;
  if (spec.layers < 1) return R::Error("the number of layers must be >= 1");
  if (!(spec.growth > 0) || !std::isfinite(spec.growth))
    return R::Error("the growth ratio must be > 0");
  if (spec.first_height > 0) {
    if (!std::isfinite(spec.first_height)) return R::Error("the first-layer height must be finite");
    double total = 0, h = spec.first_height;
    for (int k = 0; k < spec.layers; ++k, h *= spec.growth) total += h;
    if (!std::isfinite(total)) return R::Error("the total thickness overflows");
    return std::vector<double>(nv, total);
  }
  if (!(spec.first_height == 0))
    return R::Error("the first-layer height must be > 0 (or 0 to use the fraction)");
  if (!(spec.thickness_fraction > 0) || !std::isfinite(spec.thickness_fraction))
    return R::Error("the thickness fraction must be > 0");
  if (radius.size() != nv)
    return R::Error("" + std::to_string(radius.size()) + " radii for " + std::to_string(nv) +
                    " wall vertices");
  std::vector<double> t(nv);
  for (size_t v = 0; v < nv; ++v) {
    if (!(radius[v] > 0) || !std::isfinite(radius[v]))
      return R::Error("the radius at wall vertex " + std::to_string(v) +
                      " is not a positive number");
    t[v] = spec.thickness_fraction * radius[v];
  }
  return t;
}

std::vector<double> layer_fractions(const LayerSpec& spec) {
  const int n = spec.layers;
  std::vector<double> f(size_t(n) + 1, 0.0);
  double sum = 0, h = 1;
  for (int k = 1; k <= n; ++k, h *= spec.growth) f[size_t(k)] = (sum += h);
  for (int k = 1; k <= n; ++k) f[size_t(k)] /= sum;
  f[size_t(n)] = 1;
  return f;
}

void grade_reduction(const SurfaceMesh& wall, const layers::VertexRings& rings,
                     const std::vector<double>& requested, double gradation, double min_factor,
                     std::vector<double>& factor) {
  const size_t nv = wall.num_vertices();
  // Achieved thickness, relaxed from the reduced vertices outward (Dijkstra
  // by increasing thickness): a(v) <= a(u) + g |uv| for every reduced u.
  std::vector<double> achieved(nv);
  using Item = std::pair<double, int32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;  // thinnest first
  for (size_t v = 0; v < nv; ++v) {
    factor[v] = std::max(factor[v], min_factor);
    achieved[v] = factor[v] * requested[v];
    if (factor[v] < 1) heap.push({achieved[v], int32_t(v)});
  }
  while (!heap.empty()) {
    const auto [a, u] = heap.top();
    heap.pop();
    if (a > achieved[size_t(u)]) continue;  // stale
    const Vec3 pu = at(wall.points, u);
    for (int32_t i = rings.offsets[size_t(u)]; i < rings.offsets[size_t(u) + 1]; ++i) {
      const int32_t v = rings.ids[size_t(i)];
      const double cand = a + gradation * norm(at(wall.points, v) - pu);
      if (cand < achieved[size_t(v)]) {
        achieved[size_t(v)] = cand;
        factor[size_t(v)] = std::max(cand / requested[size_t(v)], min_factor);
        heap.push({cand, v});
      }
    }
  }
}

}  // namespace vm
