// Refining a layer's columns to a refined wall/front triangulation (see
// refine_layers.h; Marchandise et al., section 2.2): barycentric columns for
// the new vertices, rims extended, prisms rebuilt and checked exactly.
#include "core/layers/refine_layers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "core/geom/predicates.h"
#include "core/layers/layer_geometry.h"
#include "core/mesh/prism_split.h"

namespace vm {
using namespace layers;  // NOLINT: the layer stage's own vector helpers

Result<LayerMesh> refine_layer_columns(const LayerMesh& m, const std::vector<int32_t>& triangles,
                                       const std::vector<int32_t>& parent,
                                       const std::vector<double>& new_points, int at_layer) {
  using R = Result<LayerMesh>;
  const size_t nv = m.wall_vertices, nt = m.wall_triangles, n_new = new_points.size() / 3;
  const size_t nv2 = nv + n_new, n_layers = size_t(m.layers);
  const size_t nt2 = triangles.size() / 3;
  if (triangles.size() % 3 != 0 || new_points.size() % 3 != 0 || parent.size() != nt2)
    return R::Error("refine layers: sizes of triangles, parents and new points do not match");
  if (at_layer < 0 || at_layer > m.layers)
    return R::Error("refine layers: at_layer must be in [0, layers]");
  for (int32_t v : triangles)
    if (v < 0 || size_t(v) >= nv2) return R::Error("refine layers: a column id is out of range");
  for (int32_t p : parent)
    if (p < 0 || size_t(p) >= nt) return R::Error("refine layers: a parent is out of range");
  const int32_t top = m.layer_vertex(0, m.layers);
  auto wall_tri = [&](int32_t t) {
    const int32_t* f = &m.front[3 * size_t(t)];
    return std::array<int32_t, 3>{f[0] - top, f[1] - top, f[2] - top};
  };
  auto old_point = [&](int32_t v, size_t k) { return at(m.points, m.layer_vertex(v, int(k))); };

  // Phase 1: each new column's parent and barycentric coordinates there.
  std::vector<int32_t> column_parent(n_new, -1);
  for (size_t t = 0; t < nt2; ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t v = triangles[3 * t + size_t(k)];
      if (size_t(v) >= nv && column_parent[size_t(v) - nv] < 0)
        column_parent[size_t(v) - nv] = parent[t];
    }
  std::vector<std::array<double, 3>> lambda(n_new);
  for (size_t j = 0; j < n_new; ++j) {
    if (column_parent[j] < 0)
      return R::Error("refine layers: new column " + std::to_string(j) + " is in no triangle");
    const auto w = wall_tri(column_parent[j]);
    const Vec3 a = old_point(w[0], size_t(at_layer)), b = old_point(w[1], size_t(at_layer)),
               c = old_point(w[2], size_t(at_layer));
    const Vec3 s = at(new_points, int32_t(j));
    const Vec3 u = b - a, v = c - a, d = s - a;
    const double uu = dot(u, u), uv = dot(u, v), vv = dot(v, v), du = dot(d, u), dv = dot(d, v);
    const double det = uu * vv - uv * uv;
    if (!(det > 0)) return R::Error("refine layers: a parent triangle is degenerate");
    std::array<double, 3> l = {0, (vv * du - uv * dv) / det, (uu * dv - uv * du) / det};
    l[0] = 1 - l[1] - l[2];
    double sum = 0;
    for (double& x : l) {
      if (x < 1e-9) x = 0;
      x = std::min(x, 1.0);
      sum += x;
    }
    for (double& x : l) x /= sum;
    lambda[j] = l;
  }
  // A column shared by triangles of other parents must lie on what they
  // share with its parent (an edge or a vertex).
  for (size_t t = 0; t < nt2; ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t v = triangles[3 * t + size_t(k)];
      if (size_t(v) < nv || parent[t] == column_parent[size_t(v) - nv]) continue;
      const auto w = wall_tri(column_parent[size_t(v) - nv]), other = wall_tri(parent[t]);
      for (int i = 0; i < 3; ++i)
        if (lambda[size_t(v) - nv][size_t(i)] > 0 &&
            std::find(other.begin(), other.end(), w[size_t(i)]) == other.end())
          return R::Error("refine layers: new column " + std::to_string(size_t(v) - nv) +
                          " is not on the boundary its triangles' parents share");
    }

  // Phase 2: points and per-vertex values.
  LayerMesh out;
  out.layers = m.layers;
  out.outward = m.outward;
  out.wall_vertices = nv2;
  out.wall_triangles = nt2;
  out.fraction = m.fraction;
  out.points.resize(3 * nv2 * (n_layers + 1));
  for (size_t k = 0; k <= n_layers; ++k) {
    for (size_t v = 0; v < nv; ++v)
      put(out.points, out.layer_vertex(int32_t(v), int(k)), old_point(int32_t(v), k));
    for (size_t j = 0; j < n_new; ++j) {
      Vec3 p;
      if (int(k) == at_layer) {
        p = at(new_points, int32_t(j));
      } else {
        const auto w = wall_tri(column_parent[j]);
        p = {0, 0, 0};
        for (int i = 0; i < 3; ++i) p = p + lambda[j][size_t(i)] * old_point(w[size_t(i)], k);
      }
      put(out.points, out.layer_vertex(int32_t(nv + j), int(k)), p);
    }
  }
  out.directions = m.directions;
  out.requested_thickness = m.requested_thickness;
  out.factor = m.factor;
  out.directions.resize(3 * nv2);
  out.requested_thickness.resize(nv2);
  out.factor.resize(nv2);
  out.thickness.resize(nv2);
  for (size_t j = 0; j < n_new; ++j) {
    const auto w = wall_tri(column_parent[j]);
    Vec3 d{0, 0, 0};
    double req = 0, f = 0;
    for (int i = 0; i < 3; ++i) {
      const double l = lambda[j][size_t(i)];
      d = d + l * at(m.directions, w[size_t(i)]);
      req += l * m.requested_thickness[size_t(w[size_t(i)])];
      f += l * m.factor[size_t(w[size_t(i)])];
    }
    put(out.directions, int32_t(nv + j), normalized(d));
    out.requested_thickness[nv + j] = req;
    out.factor[nv + j] = f;
  }
  for (size_t v = 0; v < nv2; ++v)
    out.thickness[v] =
        norm(at(out.points, out.layer_vertex(int32_t(v), m.layers)) - at(out.points, int32_t(v)));

  // Phase 3: prisms and front over the refined triangles.
  build_prisms_and_front(out, triangles);

  // Phase 4: rims with the new columns on their edges, in edge order.
  for (const LayerOpening& op : m.openings) {
    LayerOpening o = op;
    o.rim.clear();
    o.columns.clear();
    const size_t n = op.rim.size();
    std::vector<std::vector<std::pair<double, int32_t>>> on_edge(n);
    std::vector<int32_t> pos(nv, -1);
    for (size_t i = 0; i < n; ++i) pos[size_t(op.rim[i])] = int32_t(i);
    for (size_t j = 0; j < n_new; ++j) {
      const auto w = wall_tri(column_parent[j]);
      int zero = -1;
      for (int i = 0; i < 3; ++i)
        if (lambda[j][size_t(i)] == 0) zero = i;
      if (zero < 0) continue;
      const int32_t a = w[size_t((zero + 1) % 3)], b = w[size_t((zero + 2) % 3)];
      if (pos[size_t(a)] < 0 || pos[size_t(b)] < 0) continue;
      const size_t ia = size_t(pos[size_t(a)]), ib = size_t(pos[size_t(b)]);
      if ((ia + 1) % n == ib)
        on_edge[ia].push_back({lambda[j][size_t((zero + 2) % 3)], int32_t(nv + j)});
      else if ((ib + 1) % n == ia)
        on_edge[ib].push_back({lambda[j][size_t((zero + 1) % 3)], int32_t(nv + j)});
    }
    for (size_t i = 0; i < n; ++i) {
      o.rim.push_back(op.rim[i]);
      std::sort(on_edge[i].begin(), on_edge[i].end());
      for (const auto& [t, v] : on_edge[i]) o.rim.push_back(v);
    }
    for (int32_t v : o.rim)
      for (size_t k = 0; k <= n_layers; ++k) o.columns.push_back(out.layer_vertex(v, int(k)));
    out.openings.push_back(std::move(o));
  }

  // Phase 5: every sub-tetrahedron strictly positive (exact).
  for (size_t p = 0; p < out.num_prisms(); ++p)
    for (const auto& tet : split_prism(&out.prisms[6 * p])) {
      const double* q[4];
      for (int k = 0; k < 4; ++k) q[k] = &out.points[3 * size_t(tet[size_t(k)])];
      if (!(orient3d(q[0], q[1], q[2], q[3]) < 0))
        return R::Error("refine layers: a refined prism near (" + std::to_string(q[0][0]) + ", " +
                        std::to_string(q[0][1]) + ", " + std::to_string(q[0][2]) +
                        ") is not positive");
    }
  return out;
}

}  // namespace vm
