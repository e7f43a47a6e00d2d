// Delaunay refinement (Chew 1989; Ruppert, J. Algorithms 18, 1995) with the
// boundary frozen: bad triangles, by size relative to the size field or by
// smallest angle, get their circumcenter inserted by Lawson insertion into
// the constrained triangulation (triangulation2d.h), in passes.
#include "core/mesh2d/delaunay_refinement.h"

#include <cmath>
#include <numbers>
#include <unordered_set>

#include "core/mesh2d/triangulation2d.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

using detail::Circle;
using detail::Triangulation;

uint64_t triple_key(std::array<int32_t, 3> v) {
  std::sort(v.begin(), v.end());
  return (uint64_t(uint32_t(v[0])) * 0x9E3779B97F4A7C15ULL) ^
         (uint64_t(uint32_t(v[1])) * 0xC2B2AE3D27D4EB4FULL) ^ uint64_t(uint32_t(v[2]));
}

}  // namespace

Result<Mesh2D> delaunay_refinement(const std::vector<double>& points,
                                   const std::vector<int32_t>& segments, const SizeField2D& size,
                                   const RefinementOptions& options) {
  if (points.size() / 2 < 3) return Result<Mesh2D>::Error("refinement needs at least 3 points");
  Triangulation tr(points);
  std::vector<int32_t> alias;
  Status st = detail::build_constrained(points, segments, tr, alias);
  if (!st.ok()) return st;

  const double sin_min = pm::sin(options.min_angle_degrees * std::numbers::pi / 180);
  const double max_ratio = 1.0 / (2 * sin_min);  // circumradius / shortest edge
  std::unordered_set<uint64_t> tried;            // circumcenter already tried
  size_t inserted = 0;
  for (int pass = 0; pass < 200; ++pass) {
    size_t inserted_this_pass = 0;
    // Triangles created during a pass wait for the next one, so a pass ends.
    const int32_t count = int32_t(tr.num_triangles());
    for (int32_t t = 0; t < count; ++t) {
      const auto& T = tr.tri(t);
      if (!T.in || tr.has_super_vertex(t)) continue;
      const double *a = tr.pt(T.v[0]), *b = tr.pt(T.v[1]), *c = tr.pt(T.v[2]);
      double g[2] = {(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3};
      double h = size(g[0], g[1]);
      if (!(h > 0)) return Result<Mesh2D>::Error("the size field must be positive");
      // The frozen boundary bounds what can be reached next to it: a
      // triangle on a boundary edge is judged against that edge's length
      // (else its centroid would be inserted again and again).
      for (int k = 0; k < 3; ++k) {
        if (!T.c[k]) continue;
        const double *p = tr.pt(T.v[(k + 1) % 3]), *q = tr.pt(T.v[(k + 2) % 3]);
        h = std::max(h, pm::hypot(p[0] - q[0], p[1] - q[1]));
      }
      Circle cc = detail::circumcircle(a, b, c);
      const double e2[3] = {(a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]),
                            (b[0] - c[0]) * (b[0] - c[0]) + (b[1] - c[1]) * (b[1] - c[1]),
                            (c[0] - a[0]) * (c[0] - a[0]) + (c[1] - a[1]) * (c[1] - a[1])};
      const double shortest2 = std::min({e2[0], e2[1], e2[2]});
      const double longest2 = std::max({e2[0], e2[1], e2[2]});
      // Size by the longest edge (a sliver has a huge circumradius but is
      // not too large; its shape is the angle criterion's business).
      const double l_target = options.size_tolerance * h;
      bool too_large = longest2 > l_target * l_target;
      bool too_poor = cc.r2 > max_ratio * max_ratio * shortest2 && shortest2 > 0.25 * h * h;
      if (!too_large && !too_poor) continue;
      // Candidate: the circumcenter, unless outside the domain or tried.
      uint64_t key = triple_key(T.v);
      double q[2] = {cc.cx, cc.cy};
      bool use_centroid = !std::isfinite(q[0]) || !std::isfinite(q[1]) || tried.count(key);
      if (!use_centroid) {
        int32_t s = tr.find_triangle(q);
        use_centroid = !tr.tri(s).in || tr.has_super_vertex(s);
        tried.insert(key);
      }
      if (use_centroid) {
        if (!too_large) continue;  // poor but small: leave it
        // On the boundary with its circumcenter outside: the boundary edge is
        // encroached and cannot be split (it is shared with the neighbor
        // patch); a centroid would only make a flatter triangle on the same
        // edge, again and again. Accept the triangle.
        if (T.c[0] || T.c[1] || T.c[2]) continue;
        q[0] = g[0];
        q[1] = g[1];
      }
      // The boundary is frozen: never insert on a boundary edge or inside its
      // diametral circle (Ruppert would split such an encroached edge; here
      // the point is rejected and the triangle accepted as it is).
      int32_t s = tr.find_triangle(q);
      if (!tr.tri(s).in || detail::encroaches(tr, s, q)) continue;
      int32_t v = tr.add_point(q[0], q[1]);
      tr.insert(v);
      ++inserted_this_pass;
      if (++inserted > options.max_inserted)
        return Result<Mesh2D>::Error("refinement stopped: more than " +
                                     std::to_string(options.max_inserted) + " points inserted");
    }
    if (inserted_this_pass == 0) break;
  }
  return detail::extract_mesh(tr, points);
}

}  // namespace vm
