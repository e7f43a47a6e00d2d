// Sliding the wall's Steiner points along their edges (see
// slide_wall_points.h; our own method). Phases: the elements and wall
// triangles touching each column; per column, the samples of t scored and
// the best valid one kept.
#include "core/layers/slide_wall_points.h"

#include <algorithm>

#include "core/geom/predicates.h"
#include "core/mesh/prism_split.h"
#include "core/quality/tet_quality.h"
#include "core/quality/triangle_quality.h"

namespace vm {
namespace {

constexpr double kLowest = 0.2, kHighest = 0.8;
constexpr int kSamples = 41;

// What one column touches: element and wall triangle indices.
struct Touching {
  std::vector<int32_t> tets, prisms, walls;
};

void add_once(std::vector<int32_t>& list, int32_t e) {
  if (list.empty() || list.back() != e) list.push_back(e);
}

}  // namespace

SlideStats slide_wall_points(VolumeMesh& m, const std::vector<WallPointColumn>& columns,
                             int32_t wall_tag) {
  SlideStats st;
  if (columns.empty()) return st;
  // Phase 1: one scan of the elements for all columns.
  std::vector<int32_t> owner(m.num_vertices(), -1);
  for (size_t c = 0; c < columns.size(); ++c)
    for (size_t i = 0; i < columns[c].points.size(); i += 3)
      owner[size_t(columns[c].points[i])] = int32_t(c);
  std::vector<Touching> touching(columns.size());
  for (size_t t = 0; t < m.num_tets(); ++t)
    for (int k = 0; k < 4; ++k)
      if (const int32_t c = owner[size_t(m.tets[4 * t + size_t(k)])]; c >= 0)
        add_once(touching[size_t(c)].tets, int32_t(t));
  for (size_t p = 0; p < m.num_prisms(); ++p)
    for (int k = 0; k < 6; ++k)
      if (const int32_t c = owner[size_t(m.prisms[6 * p + size_t(k)])]; c >= 0)
        add_once(touching[size_t(c)].prisms, int32_t(p));
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    if (m.triangle_tag[t] != wall_tag) continue;
    for (int k = 0; k < 3; ++k) {
      const int32_t v = m.triangles[3 * t + size_t(k)];
      if (owner[size_t(v)] >= 0 && columns[size_t(owner[size_t(v)])].points[0] == v)
        add_once(touching[size_t(owner[size_t(v)])].walls, int32_t(t));
    }
  }

  auto P = [&](int32_t v) { return &m.points[3 * size_t(v)]; };
  auto wall_min = [&](const Touching& to) {
    double q = 1;
    for (int32_t t : to.walls) {
      const int32_t* v = &m.triangles[3 * size_t(t)];
      q = std::min(q, triangle_gamma(P(v[0]), P(v[1]), P(v[2])));
    }
    return q;
  };
  // The smallest gamma_t of the touching tetrahedra, or -1 when an element
  // is not strictly positive.
  auto volume_min = [&](const Touching& to) {
    double q = 1;
    for (int32_t t : to.tets) {
      const int32_t* v = &m.tets[4 * size_t(t)];
      if (!(orient3d(P(v[0]), P(v[1]), P(v[2]), P(v[3])) < 0)) return -1.0;
      q = std::min(q, tet_gamma(P(v[0]), P(v[1]), P(v[2]), P(v[3])));
    }
    for (int32_t p : to.prisms)
      for (const auto& v : split_prism(&m.prisms[6 * size_t(p)]))
        if (!(orient3d(P(v[0]), P(v[1]), P(v[2]), P(v[3])) < 0)) return -1.0;
    return q;
  };

  // Phase 2: per column, the best sample.
  std::vector<double> saved;
  for (size_t c = 0; c < columns.size(); ++c) {
    const std::vector<int32_t>& pts = columns[c].points;
    const Touching& to = touching[c];
    if (to.walls.empty()) continue;
    saved.clear();
    for (size_t i = 0; i < pts.size(); i += 3) saved.insert(saved.end(), P(pts[i]), P(pts[i]) + 3);
    auto place = [&](double t) {
      for (size_t i = 0; i < pts.size(); i += 3) {
        const double *a = P(pts[i + 1]), *b = P(pts[i + 2]);
        double* x = P(pts[i]);
        for (int k = 0; k < 3; ++k) x[k] = a[k] + t * (b[k] - a[k]);
      }
    };
    const double before = wall_min(to), floor = volume_min(to);
    st.wall_min = std::min(st.wall_min, before);
    double best = before, best_t = -1;
    for (int s = 0; s < kSamples; ++s) {
      const double t = kLowest + (kHighest - kLowest) * s / (kSamples - 1);
      place(t);
      const double q = wall_min(to);
      if (q > best && floor >= 0 && volume_min(to) >= floor) best = q, best_t = t;
    }
    if (best_t >= 0) {
      place(best_t);
      ++st.moved;
    } else {
      for (size_t i = 0; i < pts.size(); i += 3) std::copy_n(&saved[i], 3, P(pts[i]));
    }
    st.wall_min_after = std::min(st.wall_min_after, wall_min(to));
  }
  return st;
}

}  // namespace vm
