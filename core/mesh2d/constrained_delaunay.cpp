// Constrained Delaunay triangulation in three phases:
//  1. Delaunay triangulation by Lawson's incremental insertion (split the
//     triangle or edge containing the point, then flip illegal edges) inside
//     a large enclosing triangle, points in a shuffled order, located by a
//     stochastic visibility walk.
//  2. Segment recovery by flips (Sloan, "A fast algorithm for generating
//     constrained Delaunay triangulations", Computers & Structures 47, 1993),
//     then Lawson flips of the unconstrained edges until all are legal.
//  3. Region classification by the parity of segments crossed from outside.
// All orientation and circle tests are the exact predicates of geom/.
#include "core/mesh2d/constrained_delaunay.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <string>

#include "core/geom/predicates.h"
#include "core/mesh2d/triangulation2d.h"

namespace vm {

using detail::Triangulation;

namespace detail {

Status build_constrained(const std::vector<double>& points, const std::vector<int32_t>& segments,
                         Triangulation& tr, std::vector<int32_t>& alias) {
  const size_t n = points.size() / 2;
  double lo[2] = {points[0], points[1]}, hi[2] = {points[0], points[1]};
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 2; ++k) {
      double x = points[2 * i + k];
      if (!std::isfinite(x)) return Status::Error("non-finite point coordinate");
      lo[k] = std::min(lo[k], x);
      hi[k] = std::max(hi[k], x);
    }
  for (int32_t s : segments)
    if (s < 0 || size_t(s) >= n) return Status::Error("segment index out of range");
  double size = std::max({hi[0] - lo[0], hi[1] - lo[1], 1e-300});
  tr.init_super(0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), size);
  // Phase 1: insert in a shuffled order (deterministic).
  std::vector<int32_t> order(n);
  alias.assign(n, -1);
  for (size_t i = 0; i < n; ++i) order[i] = int32_t(i);
  uint64_t s = 88172645463325252ULL;
  for (size_t i = n - 1; i > 0; --i) {
    s ^= s << 13, s ^= s >> 7, s ^= s << 17;
    std::swap(order[i], order[s % (i + 1)]);
  }
  for (int32_t v : order) alias[v] = tr.insert(v);
  // Phase 2: segments.
  for (size_t i = 0; i + 1 < segments.size(); i += 2) {
    int32_t a = alias[segments[i]], b = alias[segments[i + 1]];
    if (a == b) continue;
    if (!tr.recover(a, b))
      return Status::Error("segments cross each other (segment " + std::to_string(i / 2) + ")");
  }
  tr.make_delaunay();
  // Phase 3: regions.
  tr.classify_regions();
  return Status::Ok();
}

}  // namespace detail

Result<Mesh2D> constrained_delaunay(const std::vector<double>& points,
                                    const std::vector<int32_t>& segments) {
  Mesh2D out;
  out.points = points;
  if (points.size() / 2 < 3) return out;
  Triangulation tr(points);
  std::vector<int32_t> alias;
  Status st = detail::build_constrained(points, segments, tr, alias);
  if (!st.ok()) return st;
  out.triangles = segments.empty() ? tr.all_real_triangles() : tr.inside_triangles();
  return out;
}

}  // namespace vm
