// The size field of the remeshing stage (Marchandise et al., eq. 11) in
// phases: base size (uniform or 2 pi R / N), curvature limit, clamps, then
// gradation by a Dijkstra-like sweep over the input edges (Borouchaki,
// Hecht and Frey, "Mesh gradation control", 1998: h_j <= h_i + g |x_i x_j|).
#include "core/surface/size_field.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <queue>

#include "core/surface/vessel_radius.h"

namespace vm {
namespace {

/// Vertex -> neighbor vertices (CSR).
void vertex_neighbors(const SurfaceMesh& m, std::vector<int32_t>& off, std::vector<int32_t>& nb) {
  const size_t nv = m.num_vertices();
  off.assign(nv + 1, 0);
  for (int32_t v : m.triangles) off[size_t(v) + 1] += 2;
  for (size_t i = 0; i < nv; ++i) off[i + 1] += off[i];
  nb.resize(size_t(off[nv]));
  std::vector<int32_t> fill(off.begin(), off.end() - 1);
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (int c = 0; c < 3; ++c) {
      int32_t a = m.triangles[3 * t + c], b = m.triangles[3 * t + (c + 1) % 3];
      nb[size_t(fill[size_t(a)]++)] = b;
      nb[size_t(fill[size_t(b)]++)] = a;
    }
}

/// Largest principal curvature per vertex, from the angle between vertex
/// normals across each edge: kappa ~ angle / length, maximized.
std::vector<double> max_curvature(const SurfaceMesh& m, const std::vector<int32_t>& off,
                                  const std::vector<int32_t>& nb) {
  const size_t nv = m.num_vertices();
  std::vector<Eigen::Vector3d> n(nv, Eigen::Vector3d::Zero());
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t* v = &m.triangles[3 * t];
    Eigen::Vector3d a(&m.points[3 * size_t(v[0])]), b(&m.points[3 * size_t(v[1])]),
        c(&m.points[3 * size_t(v[2])]);
    Eigen::Vector3d an = (b - a).cross(c - a);  // area-weighted
    for (int k = 0; k < 3; ++k) n[size_t(v[k])] += an;
  }
  for (auto& x : n) x.normalize();
  std::vector<double> k(nv, 0.0);
  for (size_t v = 0; v < nv; ++v) {
    Eigen::Vector3d p(&m.points[3 * v]);
    double sum = 0;
    int count = 0;
    for (int32_t i = off[v]; i < off[v + 1]; ++i) {
      const size_t w = size_t(nb[size_t(i)]);
      Eigen::Vector3d d = Eigen::Vector3d(&m.points[3 * w]) - p;
      double len2 = d.squaredNorm();
      if (len2 <= 0) continue;
      // Normal curvature along the edge: 2 n.d / |d|^2 (osculating circle).
      sum += std::abs(2 * n[v].dot(d)) / len2;
      ++count;
    }
    k[v] = count ? sum / count * 2 : 0;  // twice the mean normal curvature ~ kappa_max
  }
  return k;
}

/// Gradation, smallest sizes first: h_w <= h_v + gradation |x_v x_w| along
/// the edges (off/nb: vertex_neighbors).
void grade_sizes(const SurfaceMesh& m, const std::vector<int32_t>& off,
                 const std::vector<int32_t>& nb, std::vector<double>& h, double gradation) {
  if (!(gradation > 0)) return;
  using Item = std::pair<double, int32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  for (size_t v = 0; v < h.size(); ++v) q.push({h[v], int32_t(v)});
  while (!q.empty()) {
    auto [hv, v] = q.top();
    q.pop();
    if (hv > h[size_t(v)]) continue;
    for (int32_t i = off[size_t(v)]; i < off[size_t(v) + 1]; ++i) {
      const size_t w = size_t(nb[size_t(i)]);
      double d = 0;
      for (int c = 0; c < 3; ++c) {
        double e = m.points[3 * w + c] - m.points[3 * size_t(v) + c];
        d += e * e;
      }
      double limit = hv + gradation * std::sqrt(d);
      if (limit < h[w]) {
        h[w] = limit;
        q.push({limit, int32_t(w)});
      }
    }
  }
}

}  // namespace

void limit_gradation(const SurfaceMesh& m, std::vector<double>& h, double gradation) {
  std::vector<int32_t> off, nb;
  vertex_neighbors(m, off, nb);
  grade_sizes(m, off, nb, h, gradation);
}

Result<std::vector<double>> vertex_sizes(const SurfaceMesh& m, const SizeOptions& o) {
  if (o.mode != SizeMode::kPerCircumference || m.num_triangles() == 0)
    return vertex_sizes(m, o, {});
  const std::vector<double> r = vessel_radius(m);
  return vertex_sizes(m, o, r);
}

Result<std::vector<double>> vertex_sizes(const SurfaceMesh& m, const SizeOptions& o,
                                         std::span<const double> r) {
  using R = Result<std::vector<double>>;
  if (m.num_triangles() == 0) return R::Error("the surface is empty");
  if (!(o.size_min >= 0) || !(o.size_max > 0) || o.size_min > o.size_max)
    return Status::BadOption("size_min", "must be >= 0 and at most {size_max}");
  if (!(o.gradation >= 0) || !std::isfinite(o.gradation))
    return R::Error("the gradation must be a finite number >= 0");
  if (!(o.curvature_points >= 0) || !std::isfinite(o.curvature_points))
    return R::Error("the curvature setting must be a finite number >= 0");
  const size_t nv = m.num_vertices();
  std::vector<double> h(nv);
  // Phase 1: base size.
  if (o.mode == SizeMode::kUniform) {
    if (!(o.size > 0) || !std::isfinite(o.size))
      return Status::BadOption("size", "must be a positive number");
    std::fill(h.begin(), h.end(), o.size);
  } else {
    if (!(o.per_circumference >= 3) || !std::isfinite(o.per_circumference))
      return Status::BadOption("per_circumference", "must be a number >= 3");
    if (r.size() != nv) return Status::Internal("the size field got no radius per vertex");
    for (size_t v = 0; v < nv; ++v) h[v] = 2 * std::numbers::pi * r[v] / o.per_circumference;
  }
  std::vector<int32_t> off, nb;
  vertex_neighbors(m, off, nb);
  // Phase 2: curvature limit.
  if (o.curvature_points > 0) {
    std::vector<double> k = max_curvature(m, off, nb);
    for (size_t v = 0; v < nv; ++v)
      if (k[v] > 0) h[v] = std::min(h[v], 2 * std::numbers::pi / (o.curvature_points * k[v]));
  }
  // Phase 3: clamps, then the refinement spheres (below size_min if asked).
  for (double& x : h) x = std::clamp(x, o.size_min, o.size_max);
  for (const RefineSphere& s : o.spheres)
    if (!(s.radius > 0) || !(s.size > 0) || !std::isfinite(s.radius) || !std::isfinite(s.size))
      return Status::BadOption("refine", "needs a positive radius R and size H");
  if (!o.spheres.empty())
    for (size_t v = 0; v < nv; ++v)
      h[v] = std::min(h[v], refine_size(o.spheres, &m.points[3 * v], o.gradation));
  // Phase 4: gradation.
  grade_sizes(m, off, nb, h, o.gradation);
  for (double x : h)
    if (!(x > 0) || !std::isfinite(x))
      return R::Error("the size field is not positive everywhere (check the size settings)");
  return h;
}

}  // namespace vm
