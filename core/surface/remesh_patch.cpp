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
#include "core/mesh2d/optimize2d.h"
#include "core/param/lscm.h"

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

  /// The triangle containing q (closest by barycentric slack if q sits on
  /// no triangle because of round-off) and q's barycentric coordinates.
  int32_t locate(const double* q, double bary[3]) const {
    const auto& list = cells_[index(q[1], 1) * n_ + index(q[0], 0)];
    int32_t best = -1;
    double best_slack = -1e300;
    for (int32_t t : list) {
      double w[3];
      barycentric(t, q, w);
      double slack = std::min({w[0], w[1], w[2]});
      if (slack > best_slack) {
        best_slack = slack;
        best = t;
        std::copy(w, w + 3, bary);
      }
      if (slack >= 0) break;
    }
    return best;
  }

 private:
  size_t index(double x, int k) const {
    double c = std::floor((x - lo_[k]) / cell_[k]);
    return size_t(std::clamp(c, 0.0, double(n_ - 1)));
  }
  void barycentric(int32_t t, const double* q, double w[3]) const {
    const double* p[3];
    for (int c = 0; c < 3; ++c) p[c] = &uv_[2 * size_t(m_.triangles[3 * size_t(t) + c])];
    double det =
        (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    w[1] = ((q[0] - p[0][0]) * (p[2][1] - p[0][1]) - (q[1] - p[0][1]) * (p[2][0] - p[0][0])) / det;
    w[2] = ((p[1][0] - p[0][0]) * (q[1] - p[0][1]) - (p[1][1] - p[0][1]) * (q[0] - p[0][0])) / det;
    w[0] = 1 - w[1] - w[2];
  }
  const SurfaceMesh& m_;
  const std::vector<double>& uv_;
  double lo_[2], cell_[2];
  size_t n_;
  std::vector<std::vector<int32_t>> cells_;
};

double dist3(const double* a, const double* b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

}  // namespace

Result<SurfaceMesh> remesh_disk_patch(const SurfaceMesh& m, const SizeField3D& size,
                                      PatchRemeshStats* stats, const RefinementOptions& options) {
  // Phase 1: the conformal map.
  TriangleAdjacency adj = build_adjacency(m);
  auto loops = boundary_loops(m, adj);
  if (loops.size() != 1)
    return Result<SurfaceMesh>::Error("patch remeshing needs exactly one boundary loop, found " +
                                      std::to_string(loops.size()));
  auto map = lscm(m);
  if (!map.ok()) return map.status();
  const std::vector<double>& uv = map.value().uv;
  if (map.value().flipped_triangles > 0)
    return Result<SurfaceMesh>::Error("the conformal map folds " +
                                      std::to_string(map.value().flipped_triangles) +
                                      " triangles: the patch must be split further");
  // Conformal factor per triangle (uv length / 3D length).
  std::vector<double> factor(m.num_triangles());
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t* v = &m.triangles[3 * t];
    const double *a = &m.points[3 * size_t(v[0])], *b = &m.points[3 * size_t(v[1])],
                 *c = &m.points[3 * size_t(v[2])];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
           w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double cr[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                    u[0] * w[1] - u[1] * w[0]};
    double a3 = std::sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
    const double *pa = &uv[2 * size_t(v[0])], *pb = &uv[2 * size_t(v[1])],
                 *pc = &uv[2 * size_t(v[2])];
    double a2 = (pb[0] - pa[0]) * (pc[1] - pa[1]) - (pb[1] - pa[1]) * (pc[0] - pa[0]);
    factor[t] = a3 > 0 ? std::sqrt(std::max(a2, 0.0) / a3) : 0;
  }

  // Phase 2: resample the boundary loop in 3D at the target size; points on
  // an input boundary edge map to the same fraction of its uv image.
  const auto& loop = loops[0];
  std::vector<double> pts2;  // uv of the boundary points
  std::vector<double> pts3;  // their 3D positions
  const size_t nl = loop.size();
  std::vector<double> along(nl + 1, 0.0);
  for (size_t i = 0; i < nl; ++i)
    along[i + 1] =
        along[i] + dist3(&m.points[3 * size_t(loop[i])], &m.points[3 * size_t(loop[(i + 1) % nl])]);
  // Integrate 1/h along the loop to place points at unit steps of it.
  std::vector<double> steps(nl + 1, 0.0);
  for (size_t i = 0; i < nl; ++i) {
    const double* a = &m.points[3 * size_t(loop[i])];
    const double* b = &m.points[3 * size_t(loop[(i + 1) % nl])];
    double mid[3] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
    double h = size(mid);
    if (!(h > 0)) return Result<SurfaceMesh>::Error("the size field must be positive");
    steps[i + 1] = steps[i] + (along[i + 1] - along[i]) / h;
  }
  const size_t count = std::max<size_t>(3, size_t(std::lround(steps[nl])));
  for (size_t j = 0, i = 0; j < count; ++j) {
    double target = steps[nl] * double(j) / double(count);
    while (i + 1 < nl && steps[i + 1] <= target) ++i;
    double f = steps[i + 1] > steps[i] ? (target - steps[i]) / (steps[i + 1] - steps[i]) : 0;
    size_t a = size_t(loop[i]), b = size_t(loop[(i + 1) % nl]);
    for (int k = 0; k < 3; ++k)
      pts3.push_back(m.points[3 * a + k] + f * (m.points[3 * b + k] - m.points[3 * a + k]));
    for (int k = 0; k < 2; ++k) pts2.push_back(uv[2 * a + k] + f * (uv[2 * b + k] - uv[2 * a + k]));
  }
  std::vector<int32_t> seg;
  for (size_t j = 0; j < count; ++j) seg.insert(seg.end(), {int32_t(j), int32_t((j + 1) % count)});

  // Phase 3: mesh the plane with the size pulled back by the map.
  ParamLocator locator(m, uv);
  auto to_3d = [&](const double* q, double* x) {
    double w[3];
    int32_t t = locator.locate(q, w);
    if (t < 0) return -1;
    for (int k = 0; k < 3; ++k)
      x[k] = w[0] * m.points[3 * size_t(m.triangles[3 * size_t(t)]) + k] +
             w[1] * m.points[3 * size_t(m.triangles[3 * size_t(t) + 1]) + k] +
             w[2] * m.points[3 * size_t(m.triangles[3 * size_t(t) + 2]) + k];
    return int(t);
  };
  SizeField2D size2d = [&](double u, double v) {
    double q[2] = {u, v}, x[3];
    int t = to_3d(q, x);
    if (t < 0) return 1e300;  // outside the map (cannot happen inside the domain)
    return size(x) * factor[size_t(t)];
  };
  auto plane = delaunay_refinement(pts2, seg, size2d, options);
  if (!plane.ok()) return plane.status();
  // Phase 3b: flips and smoothing in the plane; the boundary does not move.
  optimize_mesh2d(plane.value());

  // Phase 4: map back.
  SurfaceMesh out;
  const Mesh2D& p = plane.value();
  out.points.resize(3 * p.num_vertices());
  for (size_t v = 0; v < p.num_vertices(); ++v) {
    if (v < count) {
      std::copy(&pts3[3 * v], &pts3[3 * v] + 3, &out.points[3 * v]);
    } else if (to_3d(&p.points[2 * v], &out.points[3 * v]) < 0) {
      return Result<SurfaceMesh>::Error("a parametric point fell outside the map");
    }
  }
  out.triangles = p.triangles;
  if (stats) {
    stats->flipped_in_map = map.value().flipped_triangles;
    stats->boundary_points = count;
    auto [lo, hi] = std::minmax_element(factor.begin(), factor.end());
    stats->min_conformal_factor = *lo;
    stats->max_conformal_factor = *hi;
  }
  return out;
}

}  // namespace vm
