// Shrinking-ball medial radius (Ma, Bai and Kim 2012): start with a large
// ball tangent at p on the inside (center p + r n, n the inward normal); while
// the nearest surface vertex q to the center lies strictly inside the ball,
// shrink the ball to the one tangent at p through q, r = |p - q|^2 /
// (2 n . (q - p)). Nearest vertices come from a k-d tree (nanoflann).
#include "core/surface/vessel_radius.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "core/geom/point_kdtree.h"
#include "core/mesh/adjacency.h"

namespace vm {
namespace {

// Area-weighted vertex normals pointing inward (against the triangles'
// outward orientation), unit length.
std::vector<double> inward_normals(const SurfaceMesh& m) {
  std::vector<double> n(m.points.size(), 0.0);
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t* v = &m.triangles[3 * t];
    const double *a = &m.points[3 * size_t(v[0])], *b = &m.points[3 * size_t(v[1])],
                 *c = &m.points[3 * size_t(v[2])];
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double cr[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                    u[0] * w[1] - u[1] * w[0]};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d) n[3 * size_t(v[k]) + d] -= cr[d];
  }
  for (size_t i = 0; i < n.size(); i += 3) {
    double len = std::sqrt(n[i] * n[i] + n[i + 1] * n[i + 1] + n[i + 2] * n[i + 2]);
    if (len > 0)
      for (int d = 0; d < 3; ++d) n[i + d] /= len;
  }
  return n;
}

// Balls are not shrunk toward points closer than this angle to the tangent
// point, seen from the center. The wall across a tube is at about 180
// degrees; 110 rejects the staircase bumps of segmentation surfaces (tested
// on phantoms and the reference data: rim estimates within about 10%).
const double kCosSeparation = std::cos(110.0 * std::numbers::pi / 180);

}  // namespace

std::vector<double> vessel_radius(const SurfaceMesh& m) {
  const size_t nv = m.num_vertices();
  const double r_max = 0.5 * bounding_box(m.points).diagonal();
  TriangleAdjacency adj = build_adjacency(m);
  std::vector<double> normal = inward_normals(m);
  PointCloud cloud{m.points};
  PointKdTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));

  // Phase 1: shrink a ball at every vertex.
  std::vector<double> radius(nv, -1.0);  // -1: the ball never closed
  for (size_t p = 0; p < nv; ++p) {
    const double* x = &m.points[3 * p];
    const double* n = &normal[3 * p];
    double r = r_max;
    bool closed = false;
    for (int iter = 0; iter < 64; ++iter) {
      double c[3] = {x[0] + r * n[0], x[1] + r * n[1], x[2] + r * n[2]};
      uint32_t q = 0;
      double d2 = 0;
      tree.knnSearch(c, 1, &q, &d2);
      if (q == p) break;  // nothing closer than p itself: the ball is empty
      const double* y = &m.points[3 * size_t(q)];
      double pq[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
      double along = pq[0] * n[0] + pq[1] * n[1] + pq[2] * n[2];
      double len2 = pq[0] * pq[0] + pq[1] * pq[1] + pq[2] * pq[2];
      if (along <= 0) break;
      double r_new = len2 / (2 * along);
      if (!(r_new < r * (1 - 1e-12))) {  // no progress: q is on the sphere
        closed = true;
        break;
      }
      // Denoising (Ma et al., section 4): q seen from the new center within
      // a small angle of p is surface noise next to p, not the wall across
      // the lumen; keep the current ball. cos(angle p c q) = 1 - |pq|^2 /
      // (2 r^2) on the sphere of radius r through p and q.
      if (1 - len2 / (2 * r_new * r_new) > kCosSeparation) {
        closed = true;
        break;
      }
      r = r_new;
      closed = true;
    }
    if (closed) radius[p] = r;
  }

  // Phase 2: 1-ring medians (unclosed balls take their neighbors' value).
  std::vector<double> ring, next(nv);
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t v = 0; v < nv; ++v) {
      ring.clear();
      if (radius[v] > 0) ring.push_back(radius[v]);
      for (int32_t i = adj.star_offsets[v]; i < adj.star_offsets[v + 1]; ++i) {
        const int32_t* t = &m.triangles[3 * size_t(adj.star[i])];
        for (int k = 0; k < 3; ++k)
          if (size_t(t[k]) != v && radius[t[k]] > 0) ring.push_back(radius[t[k]]);
      }
      if (ring.empty()) {
        next[v] = -1;
        continue;
      }
      std::nth_element(ring.begin(), ring.begin() + ring.size() / 2, ring.end());
      next[v] = ring[ring.size() / 2];
    }
    radius.swap(next);
  }
  for (double& r : radius)
    if (!(r > 0)) r = r_max;
  return radius;
}

}  // namespace vm
