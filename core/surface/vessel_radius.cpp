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
#include <unordered_set>

#include "core/geom/point_kdtree.h"
#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/chord_radius.h"
#include "core/util/parallel.h"
#include "core/util/portable_math.h"

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
const double kCosSeparation = pm::cos(110.0 * std::numbers::pi / 180);

/// Shrinks the ball at `x` with inward normal `n`, from radius r_max,
/// against the points of `tree` (indices into `pts`); `self` is x's own
/// index in `pts`. Returns the radius, or -1 if the ball never
/// closed.
double shrink_ball(const PointKdTree& tree, const std::vector<double>& pts, const double* x,
                   const double* n, int64_t self, double r_max) {
  double r = r_max;
  bool closed = false;
  for (int iter = 0; iter < 64; ++iter) {
    double c[3] = {x[0] + r * n[0], x[1] + r * n[1], x[2] + r * n[2]};
    uint32_t q = 0;
    double d2 = 0;
    tree.knnSearch(c, 1, &q, &d2);
    if (int64_t(q) == self) break;  // nothing closer than p itself: the ball is empty
    const double* y = &pts[3 * size_t(q)];
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
    // (2 r^2) on the sphere of radius r through p and q. Not on the first
    // step: the current ball is then the initial one, half the model
    // across, which no wall touched (kept, it gave R = r_max on the sides
    // of bends and branches: up to half the vertices of real surfaces).
    if (iter > 0 && 1 - len2 / (2 * r_new * r_new) > kCosSeparation) {
      closed = true;
      break;
    }
    r = r_new;
    closed = true;
  }
  return closed ? r : -1.0;
}

/// One vertex per occupied cell of a grid of cells of edge
/// sqrt(area / samples): about `samples` vertices spread evenly on the
/// surface.
std::vector<int32_t> grid_sample(const SurfaceMesh& m, size_t samples) {
  double area = 0;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t* v = &m.triangles[3 * t];
    const Vec3 a = at(m.points, v[0]), b = at(m.points, v[1]), c = at(m.points, v[2]);
    area += 0.5 * norm(cross(b - a, c - a));
  }
  const double cell = std::sqrt(area / double(samples));
  const BoundingBox box = bounding_box(m.points);
  std::unordered_set<uint64_t> taken;
  taken.reserve(2 * samples);
  std::vector<int32_t> sample;
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    uint64_t key = 0;
    for (int k = 0; k < 3; ++k)
      key = (key << 21) | (uint64_t((m.points[3 * v + size_t(k)] - box.min[k]) / cell) & 0x1FFFFF);
    if (taken.insert(key).second) sample.push_back(int32_t(v));
  }
  return sample;
}

}  // namespace

std::vector<double> vessel_radius(const SurfaceMesh& m, const VesselRadiusSampling& sampling) {
  const size_t nv = m.num_vertices();
  const double r_max = 0.5 * bounding_box(m.points).diagonal();
  TriangleAdjacency adj = build_adjacency(m);
  std::vector<double> normal = inward_normals(m);

  // Phase 1: shrink a ball at every vertex, or at a grid sample of an
  // oversampled surface (each other vertex then takes the value of the
  // sample vertex with a closed ball nearest along the edges: a
  // breadth-first fill).
  std::vector<double> radius(nv, -1.0);  // -1: the ball never closed
  if (nv <= sampling.sample_above) {
    PointCloud cloud{m.points};
    PointKdTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    parallel_for(nv, 256, [&](size_t begin, size_t end) {
      for (size_t p = begin; p < end; ++p)
        radius[p] =
            shrink_ball(tree, m.points, &m.points[3 * p], &normal[3 * p], int64_t(p), r_max);
    });
  } else {
    // The sample's balls start at the half chord along the inward normal
    // (a ball tangent at p inside the lumen is at most that large), not at
    // the bounding box, and meet the sample's points only (a nearest-point
    // search on the full surface visits every point of the wall's ring
    // around the centre).
    const std::vector<int32_t> sample = grid_sample(m, sampling.samples);
    const std::vector<double> chord = half_chords(m, sample);
    std::vector<double> pts(3 * sample.size());
    for (size_t i = 0; i < sample.size(); ++i)
      for (size_t k = 0; k < 3; ++k) pts[3 * i + k] = m.points[3 * size_t(sample[i]) + k];
    PointCloud cloud{pts};
    PointKdTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    std::vector<int32_t> source(nv, -1), queue;
    queue.reserve(nv);
    parallel_for(sample.size(), 256, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) {
        const size_t p = size_t(sample[i]);
        const double r0 = chord[i] > 0 ? std::min(r_max, 1.001 * chord[i]) : r_max;
        radius[p] = shrink_ball(tree, pts, &m.points[3 * p], &normal[3 * p], int64_t(i), r0);
      }
    });
    for (size_t i = 0; i < sample.size(); ++i) {
      const size_t p = size_t(sample[i]);
      // Unclosed, or still the bounding-box ball (no chord, nothing met):
      // not spread, the medians fill it.
      if (!(radius[p] > 0) || radius[p] >= r_max) {
        radius[p] = -1;
        continue;
      }
      source[p] = int32_t(p);
      queue.push_back(int32_t(p));
    }
    for (size_t head = 0; head < queue.size(); ++head) {
      const int32_t v = queue[head];
      for (int32_t i = adj.star_offsets[size_t(v)]; i < adj.star_offsets[size_t(v) + 1]; ++i)
        for (int k = 0; k < 3; ++k) {
          const int32_t w = m.triangles[3 * size_t(adj.star[size_t(i)]) + size_t(k)];
          if (source[size_t(w)] >= 0) continue;
          source[size_t(w)] = source[size_t(v)];
          radius[size_t(w)] = radius[size_t(v)];
          queue.push_back(w);
        }
    }
  }

  // Phase 2: 1-ring medians (unclosed balls take their neighbors' value).
  std::vector<double> next(nv);
  for (int pass = 0; pass < 2; ++pass) {
    parallel_for(nv, 4096, [&](size_t begin, size_t end) {
      std::vector<double> ring;
      for (size_t v = begin; v < end; ++v) {
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
    });
    radius.swap(next);
  }
  for (double& r : radius)
    if (!(r > 0)) r = r_max;
  return radius;
}

}  // namespace vm
