// Verification of the boundary layer (Marchandise et al., section 2.2:
// "prevent element overlap"): exact intersection tests (geom/predicates.h,
// mesh/self_intersection.h) of the layer's closed boundary, candidates from
// a box hierarchy (mesh/triangle_bvh.h) over the front and ring triangles.
#include "core/layers/layer_verify.h"

#include <algorithm>
#include <cstddef>

#include "core/geom/predicates.h"
#include "core/layers/layer_assembly.h"
#include "core/mesh/self_intersection.h"
#include "core/mesh/triangle_bvh.h"

namespace vm {
using namespace layers;  // NOLINT: the layer stage's own vector helpers

namespace {

// Exact shortcut for neighbors (most of the pairs a smooth front has):
// triangles sharing an edge meet beyond it only if coplanar; triangles
// sharing one vertex, only if the plane of one does not have the other's
// two other corners strictly on one side. True when that proves them
// disjoint beyond what they share (triangles_intersect decides the rest).
bool separated_neighbors(const SurfaceMesh& m, size_t s, size_t t) {
  const int32_t* a = &m.triangles[3 * s];
  const int32_t* b = &m.triangles[3 * t];
  int ia[3], ib[3], shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a[i] == b[j]) ia[shared] = i, ib[shared] = j, ++shared;
  auto p = [&](int32_t v) { return &m.points[3 * size_t(v)]; };
  if (shared == 2) {
    const int c = 3 - ia[0] - ia[1], d = 3 - ib[0] - ib[1];
    return orient3d(p(a[ia[0]]), p(a[ia[1]]), p(a[c]), p(b[d])) != 0;
  }
  if (shared != 1) return false;
  auto one_side = [&](const int32_t* x, const int32_t* y, int iy) {
    const double s1 = orient3d(p(x[0]), p(x[1]), p(x[2]), p(y[(iy + 1) % 3]));
    const double s2 = orient3d(p(x[0]), p(x[1]), p(x[2]), p(y[(iy + 2) % 3]));
    return (s1 > 0 && s2 > 0) || (s1 < 0 && s2 < 0);
  };
  return one_side(a, b, ib[0]) || one_side(b, a, ia[0]);
}

}  // namespace

std::vector<int32_t> layer_intersections(const SurfaceMesh& wall, const LayerColumns& cols,
                                         const std::vector<double>& factor, int layers,
                                         const std::vector<LayerOpening>& ops, bool outward) {
  const size_t nv = wall.num_vertices(), nt = wall.num_triangles();
  SurfaceMesh shell;
  shell.points.resize(6 * nv);
  for (size_t v = 0; v < nv; ++v) {
    put(shell.points, int32_t(v), cols.point(int32_t(v), 0, factor[v]));
    put(shell.points, int32_t(nv + v), cols.point(int32_t(v), size_t(layers), factor[v]));
  }
  shell.triangles = wall.triangles;
  shell.triangles.reserve(6 * nt);
  for (int32_t v : wall.triangles) shell.triangles.push_back(v + int32_t(nv));
  // Ring faces with LayerMesh ids (k nv + v), mapped to the shell's points:
  // wall and front ids directly, intermediate rim points appended.
  std::vector<int32_t> ring_vertex;  // per ring triangle: the wall vertices of its columns
  std::vector<int32_t> ring_other;
  std::vector<int32_t> rim_pos(nv, -1);
  for (const LayerOpening& op : ops) {
    for (size_t i = 0; i < op.rim.size(); ++i) rim_pos[size_t(op.rim[i])] = int32_t(i);
    std::vector<int32_t> columns;
    for (int32_t v : op.rim)
      for (int k = 0; k <= layers; ++k) columns.push_back(int32_t(size_t(k) * nv) + v);
    const std::vector<int32_t> tris = split_quads(ring_quads_of_columns(columns, layers, outward));
    std::vector<int32_t> local(columns.size());
    for (size_t i = 0; i < op.rim.size(); ++i)
      for (int k = 0; k <= layers; ++k) {
        const int32_t v = op.rim[i];
        int32_t id;
        if (k == 0) {
          id = v;
        } else if (k == layers) {
          id = int32_t(nv) + v;
        } else {
          id = int32_t(shell.num_vertices());
          const Vec3 p = cols.point(v, size_t(k), factor[size_t(v)]);
          shell.points.insert(shell.points.end(), p.begin(), p.end());
        }
        local[i * size_t(layers + 1) + size_t(k)] = id;
      }
    for (size_t t = 0; t < tris.size(); t += 3) {
      int32_t w[2] = {-1, -1};
      int n_w = 0;
      for (int k = 0; k < 3; ++k) {
        const int32_t g = tris[t + size_t(k)];
        const int32_t v = g % int32_t(nv), layer = g / int32_t(nv);
        const size_t i = size_t(rim_pos[size_t(v)]);
        shell.triangles.push_back(local[i * size_t(layers + 1) + size_t(layer)]);
        if (n_w == 0 || (n_w == 1 && w[0] != v)) w[n_w++] = v;
      }
      ring_vertex.push_back(w[0]);
      ring_other.push_back(n_w > 1 ? w[1] : w[0]);
    }
  }
  // Every pair with a front or ring triangle, exactly (pairs within the
  // wall are the input's business): one box query per such triangle.
  const size_t n_shell = shell.num_triangles();
  std::vector<double> box(6 * n_shell);
  for (size_t t = 0; t < n_shell; ++t)
    for (int d = 0; d < 3; ++d) {
      const double a = shell.points[3 * size_t(shell.triangles[3 * t]) + size_t(d)];
      const double b = shell.points[3 * size_t(shell.triangles[3 * t + 1]) + size_t(d)];
      const double c = shell.points[3 * size_t(shell.triangles[3 * t + 2]) + size_t(d)];
      box[6 * t + size_t(d)] = std::min({a, b, c});
      box[6 * t + 3 + size_t(d)] = std::max({a, b, c});
    }
  std::vector<int32_t> involved;
  auto involve = [&](size_t t) {
    if (t < 2 * nt) {
      for (int k = 0; k < 3; ++k) involved.push_back(wall.triangles[3 * (t - nt) + size_t(k)]);
    } else {
      involved.push_back(ring_vertex[t - 2 * nt]);
      involved.push_back(ring_other[t - 2 * nt]);
    }
  };
  auto test = [&](size_t s, size_t t) {
    if (!boxes_overlap(&box[6 * s], &box[6 * s + 3], &box[6 * t], &box[6 * t + 3])) return;
    if (separated_neighbors(shell, s, t)) return;
    if (!triangles_intersect(shell, int32_t(s), int32_t(t))) return;
    if (s >= nt) involve(s);
    if (t >= nt) involve(t);
  };
  // A hierarchy over the front and rings only (pairs within the wall are
  // the input's business): their pairs by a self-traversal, as in
  // find_self_intersections; the wall's triangles by one query each.
  SurfaceMesh layer_part;
  layer_part.points = shell.points;
  layer_part.triangles.assign(shell.triangles.begin() + std::ptrdiff_t(3 * nt),
                              shell.triangles.end());
  const TriangleBvh bvh = build_triangle_bvh(layer_part, 8);
  auto id = [&](int32_t i) { return nt + size_t(bvh.order[size_t(i)]); };
  for_each_leaf_pair(bvh, [&](int32_t i, int32_t j) { test(id(i), id(j)); });
  std::vector<int32_t> nodes;
  for (size_t w = 0; w < nt; ++w) {
    const double* lo = &box[6 * w];
    const double* hi = lo + 3;
    nodes.assign(1, 0);
    while (!nodes.empty()) {
      const TriangleBvh::Node& n = bvh.nodes[size_t(nodes.back())];
      nodes.pop_back();
      if (!boxes_overlap(n.lo, n.hi, lo, hi)) continue;
      if (TriangleBvh::is_leaf(n)) {
        for (int32_t i = n.first; i < n.first + n.count; ++i) test(w, id(i));
      } else {
        nodes.push_back(n.first);
        nodes.push_back(n.first + 1);
      }
    }
  }
  return involved;
}

}  // namespace vm
