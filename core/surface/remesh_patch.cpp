// Patch remeshing by the conformal map (Marchandise et al. 2.1) in phases:
// map (param/lscm.h), boundary resampling in 3D, point location structure on
// the parametric triangulation, 2D Delaunay refinement with the size field
// pulled back to the plane (mesh2d/delaunay_refinement.h), flips and
// smoothing in the plane (mesh2d/optimize2d.h), map back.
#include "core/surface/remesh_patch.h"

#include <algorithm>
#include <cmath>

#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"
#include "core/mesh2d/adapt2d.h"
#include "core/mesh2d/frontal_delaunay.h"
#include "core/mesh2d/optimize2d.h"
#include "core/param/lscm.h"
#include "core/surface/partition.h"
#include "core/surface/resample_curve.h"

namespace vm {
namespace {

/// Uniform-grid index of the parametric triangles for point location.
class ParamLocator {
 public:
  ParamLocator(const SurfaceMesh& m, const std::vector<double>& uv) : m_(m), uv_(uv) {
    lo_[0] = lo_[1] = 1e300;
    double hi[2] = {-1e300, -1e300};
    for (size_t i = 0; i < uv.size(); i += 2)
      for (int k = 0; k < 2; ++k) {
        lo_[k] = std::min(lo_[k], uv[i + k]);
        hi[k] = std::max(hi[k], uv[i + k]);
      }
    const size_t nt = m.num_triangles();
    n_ = std::max<size_t>(1, size_t(std::sqrt(double(nt))));
    for (int k = 0; k < 2; ++k) cell_[k] = std::max((hi[k] - lo_[k]) / double(n_), 1e-300);
    cells_.assign(n_ * n_, {});
    for (size_t t = 0; t < nt; ++t) {
      double a[2] = {1e300, 1e300}, b[2] = {-1e300, -1e300};
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 2; ++k) {
          double x = uv[2 * size_t(m.triangles[3 * t + c]) + k];
          a[k] = std::min(a[k], x);
          b[k] = std::max(b[k], x);
        }
      for (size_t j = index(a[1], 1); j <= index(b[1], 1); ++j)
        for (size_t i = index(a[0], 0); i <= index(b[0], 0); ++i)
          cells_[j * n_ + i].push_back(int32_t(t));
    }
  }

  /// The triangle containing q (else the one closest by barycentric slack,
  /// with the coordinates clamped to it) and q's barycentric coordinates.
  int32_t locate(const double* q, double bary[3]) const {
    const auto& list = cells_[index(q[1], 1) * n_ + index(q[0], 0)];
    int32_t best = -1;
    double best_slack = -1e300;
    for (int32_t t : list) {
      double w[3];
      if (!barycentric(t, q, w)) continue;  // flat in the plane
      double slack = std::min({w[0], w[1], w[2]});
      if (slack > best_slack) {
        best_slack = slack;
        best = t;
        std::copy(w, w + 3, bary);
      }
      if (slack >= 0) break;
    }
    // Outside every triangle (the resampled boundary may cut across a
    // concave bend of the patch's own boundary): the closest point of the
    // best triangle, so the result stays on the surface.
    if (best >= 0 && best_slack < 0) {
      double sum = 0;
      for (int c = 0; c < 3; ++c) sum += bary[c] = std::max(bary[c], 0.0);
      for (int c = 0; c < 3; ++c) bary[c] /= sum;
    }
    return best;
  }

 private:
  size_t index(double x, int k) const {
    double c = std::floor((x - lo_[k]) / cell_[k]);
    return size_t(std::clamp(c, 0.0, double(n_ - 1)));
  }
  bool barycentric(int32_t t, const double* q, double w[3]) const {
    const double* p[3];
    for (int c = 0; c < 3; ++c) p[c] = &uv_[2 * size_t(m_.triangles[3 * size_t(t) + c])];
    double det =
        (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    w[1] = ((q[0] - p[0][0]) * (p[2][1] - p[0][1]) - (q[1] - p[0][1]) * (p[2][0] - p[0][0])) / det;
    w[2] = ((p[1][0] - p[0][0]) * (q[1] - p[0][1]) - (p[1][1] - p[0][1]) * (q[0] - p[0][0])) / det;
    w[0] = 1 - w[1] - w[2];
    return std::isfinite(w[0]) && std::isfinite(w[1]) && std::isfinite(w[2]);
  }
  const SurfaceMesh& m_;
  const std::vector<double>& uv_;
  double lo_[2], cell_[2];
  size_t n_;
  std::vector<std::vector<int32_t>> cells_;
};

}  // namespace

Result<PatchMesh> mesh_mapped_patch(const SurfaceMesh& m, const std::vector<double>& uv,
                                    const std::vector<double>& vertex_size,
                                    const std::vector<PatchBoundaryPoint>& boundary,
                                    const PatchMeshOptions& options) {
  // The conformal factor (uv length / 3D length) at each vertex, from the
  // areas of its triangles, so the planar size is continuous and positive
  // even next to degenerate input triangles.
  std::vector<double> area2(m.num_vertices(), 0.0), area3(m.num_vertices(), 0.0);
  {
    const std::vector<double> f = conformal_factors(m, uv);
    for (size_t t = 0; t < m.num_triangles(); ++t) {
      const int32_t* v = &m.triangles[3 * t];
      double a3 = 0;
      {
        const double *a = &m.points[3 * size_t(v[0])], *b = &m.points[3 * size_t(v[1])],
                     *c = &m.points[3 * size_t(v[2])];
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
               w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double cr[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                        u[0] * w[1] - u[1] * w[0]};
        a3 = std::sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
      }
      for (int c = 0; c < 3; ++c) {
        area3[size_t(v[c])] += a3;
        area2[size_t(v[c])] += f[t] * f[t] * a3;
      }
    }
  }
  double total2 = 0, total3 = 0;
  for (size_t v = 0; v < area2.size(); ++v) total2 += area2[v], total3 += area3[v];
  const double mean_factor = total3 > 0 ? std::sqrt(total2 / total3) : 1;
  std::vector<double> planar_size(m.num_vertices());
  for (size_t v = 0; v < planar_size.size(); ++v) {
    const double f = area3[v] > 0 && area2[v] > 0 ? std::sqrt(area2[v] / area3[v]) : mean_factor;
    planar_size[v] = vertex_size[v] * f;
  }
  // Phase 1: the boundary points in the plane.
  const size_t count = boundary.size();
  std::vector<double> pts2(2 * count), pts3(3 * count);
  for (size_t j = 0; j < count; ++j) {
    const auto& b = boundary[j];
    for (int k = 0; k < 3; ++k)
      pts3[3 * j + k] =
          (1 - b.t) * m.points[3 * size_t(b.a) + k] + b.t * m.points[3 * size_t(b.b) + k];
    for (int k = 0; k < 2; ++k)
      pts2[2 * j + k] = (1 - b.t) * uv[2 * size_t(b.a) + k] + b.t * uv[2 * size_t(b.b) + k];
  }
  std::vector<int32_t> seg;
  seg.reserve(2 * count);
  for (size_t j = 0; j < count; ++j) seg.insert(seg.end(), {int32_t(j), int32_t((j + 1) % count)});

  // Phase 2: mesh the plane with the size pulled back by the map.
  ParamLocator locator(m, uv);
  auto interpolate = [&](const double* q, double w[3]) { return locator.locate(q, w); };
  SizeField2D size2d = [&](double u, double v) {
    double q[2] = {u, v}, w[3];
    int32_t t = interpolate(q, w);
    if (t < 0) return 1e300;  // outside the map (cannot happen inside the domain)
    const int32_t* tv = &m.triangles[3 * size_t(t)];
    return w[0] * planar_size[size_t(tv[0])] + w[1] * planar_size[size_t(tv[1])] +
           w[2] * planar_size[size_t(tv[2])];
  };
  Result<Mesh2D> plane = options.mesher == Mesher2D::kDelaunay
                             ? delaunay_refinement(pts2, seg, size2d, options.refinement)
                         : options.mesher == Mesher2D::kFrontal
                             ? frontal_delaunay(pts2, seg, size2d, options.refinement)
                             : adapt_mesh2d(pts2, seg, size2d, options.refinement);
  if (!plane.ok()) return plane.status();
  // Phase 3: flips and smoothing in the plane; the boundary does not move.
  if (options.optimize_passes > 0) optimize_mesh2d(plane.value(), options.optimize_passes);

  // Phase 4: map back.
  PatchMesh out;
  const Mesh2D& p = plane.value();
  out.mesh.points.resize(3 * p.num_vertices());
  out.home.resize(p.num_vertices());
  for (size_t v = 0; v < p.num_vertices(); ++v) {
    double w[3];
    int32_t t = interpolate(&p.points[2 * v], w);
    if (t < 0) return Result<PatchMesh>::Error("a parametric point fell outside the map");
    out.home[v] = t;
    if (v < count) {
      std::copy(&pts3[3 * v], &pts3[3 * v] + 3, &out.mesh.points[3 * v]);
      continue;
    }
    for (int k = 0; k < 3; ++k)
      out.mesh.points[3 * v + k] = w[0] * m.points[3 * size_t(m.triangles[3 * size_t(t)]) + k] +
                                   w[1] * m.points[3 * size_t(m.triangles[3 * size_t(t) + 1]) + k] +
                                   w[2] * m.points[3 * size_t(m.triangles[3 * size_t(t) + 2]) + k];
  }
  out.mesh.triangles = p.triangles;
  return out;
}

Result<SurfaceMesh> remesh_disk_patch(const SurfaceMesh& m, const PointSizeFn& size,
                                      PatchRemeshStats* stats, const PatchMeshOptions& options) {
  TriangleAdjacency adj = build_adjacency(m);
  auto loops = boundary_loops(m, adj);
  if (loops.size() != 1)
    return Result<SurfaceMesh>::Error("patch remeshing needs exactly one boundary loop, found " +
                                      std::to_string(loops.size()));
  auto map = lscm(m);
  if (!map.ok()) return map.status();
  if (map.value().flipped_triangles > 0)
    return Result<SurfaceMesh>::Error("the conformal map folds " +
                                      std::to_string(map.value().flipped_triangles) +
                                      " triangles: the patch must be split further");
  std::vector<double> vertex_size(m.num_vertices());
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    vertex_size[v] = size(&m.points[3 * v]);
    if (!(vertex_size[v] > 0)) return Result<SurfaceMesh>::Error("the size field must be positive");
  }
  // The boundary loop resampled in 3D at the target size.
  const auto& loop = loops[0];
  std::vector<double> loop_points, loop_sizes;
  for (int32_t v : loop) {
    loop_points.insert(loop_points.end(), &m.points[3 * size_t(v)], &m.points[3 * size_t(v)] + 3);
    loop_sizes.push_back(vertex_size[size_t(v)]);
  }
  std::vector<PatchBoundaryPoint> boundary;
  for (const CurveSample& s : resample_curve(loop_points, loop_sizes, true, 3))
    boundary.push_back({loop[s.segment], loop[(s.segment + 1) % loop.size()], s.t});
  auto patch = mesh_mapped_patch(m, map.value().uv, vertex_size, boundary, options);
  if (!patch.ok()) return patch.status();
  if (stats) {
    const std::vector<double> factor = conformal_factors(m, map.value().uv);
    stats->flipped_in_map = map.value().flipped_triangles;
    stats->boundary_points = boundary.size();
    auto [lo, hi] = std::minmax_element(factor.begin(), factor.end());
    stats->min_conformal_factor = *lo;
    stats->max_conformal_factor = *hi;
  }
  return std::move(patch).value().mesh;
}

}  // namespace vm
