// Shrinking empty balls (Ma, Bai and Kim 2012) in one radius query: the
// balls tangent at p with centers along n are nested (the ball through p and
// q has radius r_q = |q - p|^2 / (2 n . (q - p))), so the largest one empty
// of counted vertices has the smallest r_q over the counted vertices inside
// the ball of the needed radius. A vertex q counts when the angle p-c_q-q at
// the center c_q of its ball, cos = 1 - |q - p|^2 / (2 r_q^2), is at least
// the separation angle (Ma et al.'s denoising: smaller angles are noise or
// gentle curvature next to p).
#include "core/layers/layer_gap.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>

#include "core/geom/point_kdtree.h"
#include "core/mesh/edge_lengths.h"
#include "core/util/portable_math.h"

namespace vm {

std::vector<double> empty_ball_radius(const SurfaceMesh& wall, const std::vector<double>& normal,
                                      const std::vector<double>& needed, double separation_degrees,
                                      bool exact) {
  const size_t nv = wall.num_vertices();
  std::vector<double> radius(needed);
  if (nv == 0) return radius;
  const double cos_sep = pm::cos(separation_degrees * std::numbers::pi / 180);
  PointCloud cloud{wall.points};
  PointKdTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  std::vector<std::pair<uint32_t, double>> found;
  const nanoflann::SearchParams unsorted(32, 0, false);
  constexpr size_t kNearest = 8, kMore = 64;
  uint32_t knn_index[kMore];
  double knn_d2[kMore];
  // Mean edge length at each vertex: the first ball tried is a few of them.
  const std::vector<double> edge = mean_edge_lengths(wall);
  for (size_t p = 0; p < nv; ++p) {
    if (!(needed[p] > 0)) continue;
    const double* x = &wall.points[3 * p];
    const double* n = &normal[3 * p];
    // The ball through p and q (r_q), if q counts and shrinks the ball.
    auto shrink_to = [&](uint32_t q, double limit) {
      if (q == p) return limit;
      const double* y = &wall.points[3 * size_t(q)];
      const double pq[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
      const double along = pq[0] * n[0] + pq[1] * n[1] + pq[2] * n[2];
      const double len2 = pq[0] * pq[0] + pq[1] * pq[1] + pq[2] * pq[2];
      if (!(along > 0)) return limit;  // not inside any of the balls
      const double rq = len2 / (2 * along);
      if (!(rq < limit)) return limit;
      if (1 - len2 / (2 * rq * rq) > cos_sep) return limit;  // next to p: not across
      return rq;
    };
    // Shrinks the ball of radius r by the nearest vertices to its center (a
    // few queries for most vertices); when the nearest ones inside are all
    // next to p and more may be inside, one radius query settles it.
    auto settle = [&](double r) {
      for (int iter = 0; iter < 64; ++iter) {
        const double c[3] = {x[0] + r * n[0], x[1] + r * n[1], x[2] + r * n[2]};
        const double inside2 = r * r * (1 - 1e-12);
        // Most balls are empty: their center's nearest vertex is p itself.
        uint32_t nearest = 0;
        double nearest_d2 = 0;
        tree.knnSearch(c, 1, &nearest, &nearest_d2);
        if (nearest == p || !(nearest_d2 < inside2)) break;
        const size_t k = tree.knnSearch(c, kNearest, knn_index, knn_d2);
        double r_new = r;
        size_t inside = 0;
        for (size_t i = 0; i < k; ++i)
          if (knn_d2[i] < inside2) ++inside, r_new = shrink_to(knn_index[i], r_new);
        if (r_new < r) {
          r = r_new;
          continue;
        }
        if (inside == kNearest && !exact) {
          // More neighbors, then the ball is taken as it is.
          const size_t k2 = tree.knnSearch(c, kMore, knn_index, knn_d2);
          for (size_t i = 0; i < k2; ++i)
            if (knn_d2[i] < inside2) r_new = shrink_to(knn_index[i], r_new);
          if (r_new < r) {
            r = r_new;
            continue;
          }
        } else if (inside == kNearest) {
          tree.radiusSearch(c, inside2, found, unsorted);
          for (const auto& item : found) r = shrink_to(item.first, r);
        }
        break;
      }
      return r;
    };
    // Balls are nested, so the answer for `needed` is the answer for the
    // first ball tried, doubled until a counted vertex shrinks it (small
    // balls keep the k-d tree queries near the wall, hence fast).
    const double start = edge[p] > 0 ? 4 * edge[p] : needed[p];
    double r = std::min(needed[p], start);
    for (;;) {
      const double settled = settle(r);
      if (settled < r || r >= needed[p]) {
        r = settled;
        break;
      }
      r = std::min(2 * r, needed[p]);
    }
    radius[p] = r;
  }
  return radius;
}

}  // namespace vm
