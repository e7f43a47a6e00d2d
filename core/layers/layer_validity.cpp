// Local prism validity and shrink by bisection (see layer_validity.h;
// Marchandise et al., section 2.2). The split of each slice by the
// smallest-index rule (mesh/prism_split.h) depends only on the order of the
// wall triangle's vertex ids, since slice k's ids are k nv + v below and
// (k + 1) nv + v above: it is computed once per triangle.
#include "core/layers/layer_validity.h"

#include <algorithm>
#include <cmath>

#include "core/mesh/prism_split.h"
#include "core/mesh/volume_mesh.h"
#include "core/quality/triangle_quality.h"

namespace vm {
using namespace layers;  // NOLINT: the layer stage's own vector helpers

namespace {
// Prism corner order of the wall triangle's corners: the bottom must see the
// top on its positive side, so it is reversed for inward layers.
constexpr int kInwardOrder[3] = {0, 2, 1};
constexpr int kOutwardOrder[3] = {0, 1, 2};
// cos 65 degrees: the most a face between two stacked prisms may lean from
// the line between their centroids.
constexpr double kMaxLeanCos = 0.42261826174069944;
}  // namespace

LayerValidity::LayerValidity(const SurfaceMesh& wall, const LayerDirections& dirs,
                             const std::vector<double>& requested,
                             const std::vector<double>& fraction, bool outward,
                             double min_volume_ratio, double min_front_quality_ratio)
    : wall_(wall),
      dirs_(dirs),
      requested_(requested),
      fraction_(fraction),
      outward_(outward),
      min_front_quality_ratio_(min_front_quality_ratio) {
  const size_t nt = wall.num_triangles();
  const int32_t nv = int32_t(wall.num_vertices());
  const int* order = outward ? kOutwardOrder : kInwardOrder;
  area_.resize(nt);
  gamma_.resize(nt);
  margin_.resize(nt);
  split_.resize(nt);
  for (size_t t = 0; t < nt; ++t) {
    const int32_t* w = &wall.triangles[3 * t];
    const Vec3 a = at(wall.points, w[0]), b = at(wall.points, w[1]), c = at(wall.points, w[2]);
    area_[t] = 0.5 * norm(cross(b - a, c - a));
    gamma_[t] = triangle_gamma(a.data(), b.data(), c.data());
    double vis = 1;
    for (int k = 0; k < 3; ++k)
      vis = std::min(vis, dot(at(dirs.direction, w[k]), at(dirs.triangle_normal, int32_t(t))));
    margin_[t] = std::max(1e-3, std::min(min_volume_ratio, 0.5 * vis));
    int32_t ids[6];
    for (int j = 0; j < 3; ++j) ids[j] = w[order[j]], ids[3 + j] = nv + w[order[j]];
    const auto tets = split_prism(ids);
    for (int e = 0; e < 3; ++e)
      for (int k = 0; k < 4; ++k) {
        const int32_t id = tets[size_t(e)][size_t(k)];
        const int base = id >= nv ? 3 : 0;
        const int32_t v = id >= nv ? id - nv : id;
        int local = 0;
        while (w[order[local]] != v) ++local;
        split_[t][size_t(4 * e + k)] = uint8_t(base + local);
      }
  }
}

double LayerValidity::score(size_t t, const double f[3], double* volume_ratio) const {
  const int32_t* w = &wall_.triangles[3 * t];
  const int* order = outward_ ? kOutwardOrder : kInwardOrder;
  Vec3 base[3], step[3];  // prism corner order
  double min_height = 1e300;
  for (int j = 0; j < 3; ++j) {
    const int32_t v = w[order[j]];
    const double h = f[order[j]] * requested_[size_t(v)];
    base[j] = at(wall_.points, v);
    step[j] = h * at(dirs_.direction, v);
    min_height = std::min(min_height, h);
  }
  double worst = 1e300, worst_ratio = 1e300;
  const size_t layers = fraction_.size() - 1;
  for (size_t k = 0; k < layers; ++k) {
    Vec3 p[6];
    for (int j = 0; j < 3; ++j) {
      p[j] = base[j] + fraction_[k] * step[j];
      p[3 + j] = base[j] + fraction_[k + 1] * step[j];
    }
    const double ref = 2 * area_[t] * (fraction_[k + 1] - fraction_[k]) * min_height;
    for (int e = 0; e < 3; ++e) {
      const uint8_t* s = &split_[t][size_t(4 * e)];
      const double v6 = tet_volume6(p[s[0]].data(), p[s[1]].data(), p[s[2]].data(), p[s[3]].data());
      const double ratio = ref > 0 ? v6 / ref : -1;
      worst_ratio = std::min(worst_ratio, ratio);
    }
  }
  worst = worst_ratio / margin_[t];
  // Orthogonality between stacked prisms: the line between their centroids
  // is the mean of the three column steps; the face between them (the
  // triangle at fraction k + 1, k + 2 < N + 1) must not lean more than
  // kMaxLean from it (finite-volume solvers count faces beyond 70 degrees as
  // severely non-orthogonal), or more than the wall itself does (so small
  // enough factors always pass: the faces tend to the wall triangle).
  if (layers > 1) {
    const Vec3 axis = step[0] + step[1] + step[2];  // 3 times the mean: only its direction matters
    const double axis_len = norm(axis);
    auto lean_cos = [&](double fr) {
      const Vec3 q0 = base[0] + fr * step[0], q1 = base[1] + fr * step[1],
                 q2 = base[2] + fr * step[2];
      const Vec3 n = cross(q1 - q0, q2 - q0);
      const double len = norm(n) * axis_len;
      return len > 0 ? dot(n, axis) / len : 1.0;
    };
    const double wall_cos = lean_cos(0);
    const double need = std::min(kMaxLeanCos, 0.9 * wall_cos);
    if (axis_len > 0 && need > 0)
      for (size_t k = 1; k < layers; ++k) worst = std::min(worst, lean_cos(fraction_[k]) / need);
  }
  if (min_front_quality_ratio_ > 0) {
    Vec3 q[3];
    for (int j = 0; j < 3; ++j) q[j] = base[j] + step[j];
    const double g = triangle_gamma(q[0].data(), q[1].data(), q[2].data());
    worst = std::min(worst, g / (min_front_quality_ratio_ * gamma_[t]));
  }
  if (volume_ratio) *volume_ratio = worst_ratio;
  return worst;
}

size_t LayerValidity::shrink_invalid(std::vector<double>& factor, std::vector<uint8_t>& lowered,
                                     double* min_ratio) const {
  const size_t nt = wall_.num_triangles();
  std::vector<double> next = factor;
  size_t failing = 0;
  double smallest = 1e300;
  for (size_t t = 0; t < nt; ++t) {
    const auto f = corner_factors(t, factor);
    double ratio = 0;
    const double sc = score(t, f.data(), &ratio);
    smallest = std::min(smallest, ratio);
    if (sc >= 1) continue;
    ++failing;
    // Cap the corners' factors at a level c (the tallest columns come down
    // first, so a corner already lowered is not lowered again merely for
    // standing next to taller ones): the largest valid c by bisection.
    double lo = 0, hi = std::max({f[0], f[1], f[2]});
    for (int iter = 0; iter < 16; ++iter) {
      const double mid = 0.5 * (lo + hi);
      const double g[3] = {std::min(f[0], mid), std::min(f[1], mid), std::min(f[2], mid)};
      (score(t, g) >= 1 ? lo : hi) = mid;
    }
    const double cap = std::max(lo, hi / 65536);
    for (int k = 0; k < 3; ++k) {
      const size_t v = size_t(wall_.triangles[3 * t + size_t(k)]);
      const double g = std::min(f[size_t(k)], cap);
      if (g < next[v]) next[v] = g, lowered[v] = 1;
    }
  }
  factor.swap(next);
  if (min_ratio) *min_ratio = smallest;
  return failing;
}

}  // namespace vm
