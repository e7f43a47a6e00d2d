// Local adaptation by edge splitting (in the spirit of Gmsh's MeshAdapt,
// Marchandise et al., section 3): passes over the interior edges, splitting
// those too long for the size field at their midpoints.
#include "core/mesh2d/adapt2d.h"

#include <cmath>

#include "core/mesh2d/triangulation2d.h"
#include "core/util/portable_math.h"

namespace vm {

Result<Mesh2D> adapt_mesh2d(const std::vector<double>& points, const std::vector<int32_t>& segments,
                            const SizeField2D& size, const RefinementOptions& options) {
  using R = Result<Mesh2D>;
  if (points.size() / 2 < 3) return R::Error("meshing needs at least 3 points");
  detail::Triangulation tr(points);
  std::vector<int32_t> alias;
  Status st = detail::build_constrained(points, segments, tr, alias);
  if (!st.ok()) return st;
  size_t inserted = 0;
  std::vector<double> midpoints;
  for (int pass = 0; pass < 100; ++pass) {
    // Collect the midpoints of the long interior edges, then insert them.
    midpoints.clear();
    for (int32_t t = 0; t < int32_t(tr.num_triangles()); ++t) {
      const auto& T = tr.tri(t);
      if (!T.in || tr.has_super_vertex(t)) continue;
      for (int k = 0; k < 3; ++k) {
        const int32_t a = T.v[(k + 1) % 3], b = T.v[(k + 2) % 3];
        if (T.c[k] || a > b) continue;  // each interior edge once
        const double *pa = tr.pt(a), *pb = tr.pt(b);
        const double m[2] = {0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])};
        const double h = size(m[0], m[1]);
        if (!(h > 0)) return R::Error("the size field must be positive");
        if (pm::hypot(pb[0] - pa[0], pb[1] - pa[1]) > options.size_tolerance * h)
          midpoints.insert(midpoints.end(), {m[0], m[1], h});
      }
    }
    size_t inserted_this_pass = 0;
    for (size_t i = 0; i < midpoints.size(); i += 3) {
      const double* q = &midpoints[i];
      int32_t s = tr.find_triangle(q);
      bool ok = tr.tri(s).in && !tr.has_super_vertex(s) && !detail::encroaches(tr, s, q);
      for (int j = 0; j < 3 && ok; ++j) {
        const double* v = tr.pt(tr.tri(s).v[j]);
        ok = pm::hypot(v[0] - q[0], v[1] - q[1]) > 0.3 * q[2];
      }
      if (!ok) continue;
      tr.insert(tr.add_point(q[0], q[1]));
      ++inserted_this_pass;
      if (++inserted > options.max_inserted)
        return R::Error("meshing stopped: more than " + std::to_string(options.max_inserted) +
                        " points inserted");
    }
    if (inserted_this_pass == 0) break;
  }
  return detail::extract_mesh(tr, points);
}

}  // namespace vm
