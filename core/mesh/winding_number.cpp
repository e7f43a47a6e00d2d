// Fast generalized winding numbers (winding_number.h).
#include "core/mesh/winding_number.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/geom/vec3.h"

namespace vm {
namespace {

/// The signed solid angle of triangle (a, b, c) seen from q (van Oosterom
/// and Strackee, "The solid angle of a plane triangle", IEEE TBME 1983),
/// positive when q is on the side its normal (b - a) x (c - a) points away
/// from.
double solid_angle(const double* a, const double* b, const double* c, const double* q) {
  double u[3], v[3], w[3];
  v3::sub(a, q, u);
  v3::sub(b, q, v);
  v3::sub(c, q, w);
  const double lu = v3::norm(u), lv = v3::norm(v), lw = v3::norm(w);
  double vw[3];
  v3::cross(v, w, vw);
  const double det = v3::dot(u, vw);
  const double den = lu * lv * lw + v3::dot(u, v) * lw + v3::dot(v, w) * lu + v3::dot(w, u) * lv;
  if (det == 0 && den <= 0) return 0;  // q on the triangle's plane, inside or on it
  return 2 * std::atan2(det, den);
}

const double* corner(const SurfaceMesh& m, int32_t t, int k) {
  return &m.points[3 * size_t(m.triangles[3 * size_t(t) + size_t(k)])];
}

}  // namespace

WindingNumberTree build_winding_number_tree(const SurfaceMesh& mesh) {
  WindingNumberTree tree;
  tree.bvh = build_triangle_bvh(mesh, 8);
  const size_t n = tree.bvh.nodes.size();
  tree.area_vector.assign(3 * n, 0);
  tree.center.assign(3 * n, 0);
  tree.reach.assign(n, 0);
  // Children follow their parent (first, first + 1 > parent): visit the
  // nodes backward so that children are done first.
  std::vector<double> weight(n, 0);  // the node's area (for its centroid)
  for (size_t i = n; i-- > 0;) {
    const TriangleBvh::Node& node = tree.bvh.nodes[i];
    double* av = &tree.area_vector[3 * i];
    double* c = &tree.center[3 * i];
    if (TriangleBvh::is_leaf(node)) {
      for (int32_t k = node.first; k < node.first + node.count; ++k) {
        const int32_t t = tree.bvh.order[size_t(k)];
        const double *a = corner(mesh, t, 0), *b = corner(mesh, t, 1), *d = corner(mesh, t, 2);
        const Vec3 x = triangle_cross(a, b, d);
        const double area = 0.5 * norm(x);
        for (int j = 0; j < 3; ++j) {
          av[j] += 0.5 * x[size_t(j)];
          c[j] += area * (a[j] + b[j] + d[j]) / 3;
        }
        weight[i] += area;
      }
    } else {
      for (int32_t child = node.first; child <= node.first + 1; ++child) {
        const size_t ch = size_t(child);
        for (int j = 0; j < 3; ++j) {
          av[j] += tree.area_vector[3 * ch + size_t(j)];
          c[j] += weight[ch] * tree.center[3 * ch + size_t(j)];
        }
        weight[i] += weight[ch];
      }
    }
    for (int j = 0; j < 3; ++j)
      c[j] = weight[i] > 0 ? c[j] / weight[i] : 0.5 * (node.lo[j] + node.hi[j]);
    double r2 = 0;
    for (int corner_bits = 0; corner_bits < 8; ++corner_bits) {
      double d2 = 0;
      for (int j = 0; j < 3; ++j) {
        const double x = ((corner_bits >> j) & 1 ? node.hi[j] : node.lo[j]) - c[j];
        d2 += x * x;
      }
      r2 = std::max(r2, d2);
    }
    tree.reach[i] = std::sqrt(r2);
  }
  return tree;
}

double winding_number(const SurfaceMesh& mesh, const WindingNumberTree& tree, const double* q,
                      double beta) {
  if (tree.bvh.empty()) return 0;
  double sum = 0;  // solid angles
  int32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const size_t i = size_t(stack[--top]);
    const TriangleBvh::Node& node = tree.bvh.nodes[i];
    double d[3];
    v3::sub(&tree.center[3 * i], q, d);
    const double dist = v3::norm(d);
    if (dist > beta * tree.reach[i]) {
      // The dipole: the solid angle of an area vector A seen at d is A.d / |d|^3.
      sum += v3::dot(&tree.area_vector[3 * i], d) / (dist * dist * dist);
      continue;
    }
    if (TriangleBvh::is_leaf(node)) {
      for (int32_t k = node.first; k < node.first + node.count; ++k) {
        const int32_t t = tree.bvh.order[size_t(k)];
        sum += solid_angle(corner(mesh, t, 0), corner(mesh, t, 1), corner(mesh, t, 2), q);
      }
    } else if (top + 2 <= 128) {
      stack[top++] = node.first;
      stack[top++] = node.first + 1;
    }
  }
  return sum / (4 * std::numbers::pi);
}

double winding_number_exact(const SurfaceMesh& mesh, const double* q) {
  double sum = 0;
  for (size_t t = 0; t < mesh.num_triangles(); ++t)
    sum += solid_angle(corner(mesh, int32_t(t), 0), corner(mesh, int32_t(t), 1),
                       corner(mesh, int32_t(t), 2), q);
  return sum / (4 * std::numbers::pi);
}

}  // namespace vm
