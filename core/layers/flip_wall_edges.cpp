// Wall edges flipped instead of split (see flip_wall_edges.h; our own
// method): the wall's test, the layers' test, the layers rebuilt.
#include "core/layers/flip_wall_edges.h"

#include <algorithm>
#include <cmath>

#include "core/geom/predicates.h"
#include "core/geom/vec3.h"
#include "core/mesh/prism_split.h"
#include "core/quality/triangle_quality.h"

namespace vm {
namespace {

Vec3 vec(const double* p) { return {p[0], p[1], p[2]}; }

}  // namespace

bool wall_flip_ok(const double* a, const double* b, const double* c, const double* d) {
  const Vec3 A = vec(a), B = vec(b), C = vec(c), D = vec(d);
  const Vec3 old1 = cross(B - A, C - A), old2 = cross(A - B, D - B);
  const Vec3 new1 = cross(A - C, D - C), new2 = cross(B - D, C - D);
  for (const Vec3& o : {old1, old2})
    for (const Vec3& n : {new1, new2})
      if (!(dot(o, n) > 0)) return false;
  // The distance between the lines ab and cd: how far the surface moves.
  const Vec3 ab = B - A, cd = D - C, w = cross(ab, cd);
  const double lw = norm(w), shorter = std::min(norm(ab), norm(cd));
  if (!(lw > 0)) return false;
  if (std::abs(dot(C - A, w)) / lw > kWallFlipGap * shorter) return false;
  const double before = std::min(triangle_gamma(a, b, c), triangle_gamma(b, a, d));
  const double after = std::min(triangle_gamma(c, a, d), triangle_gamma(d, b, c));
  return after >= before - kWallFlipQualityLoss;
}

bool layer_flip_ok(const LayerMesh& m, int32_t a, int32_t b, int32_t c, int32_t d) {
  const int32_t pair[2][3] = {{c, a, d}, {d, b, c}};
  for (int k = 0; k < m.layers; ++k)
    for (const auto& f : pair) {
      // As build_prisms_and_front orients them.
      const int32_t base[3] = {f[0], m.outward ? f[1] : f[2], m.outward ? f[2] : f[1]};
      int32_t prism[6];
      for (int j = 0; j < 3; ++j) {
        prism[j] = m.layer_vertex(base[j], k);
        prism[j + 3] = m.layer_vertex(base[j], k + 1);
      }
      for (const auto& t : split_prism(prism)) {
        const double* q[4];
        for (int j = 0; j < 4; ++j) q[j] = &m.points[3 * size_t(t[size_t(j)])];
        if (!(orient3d(q[0], q[1], q[2], q[3]) < 0)) return false;
      }
    }
  return true;
}

LayerMesh retriangulate_layer(const LayerMesh& m, const std::vector<int32_t>& triangles) {
  LayerMesh out = m;
  out.wall_triangles = triangles.size() / 3;
  build_prisms_and_front(out, triangles);
  return out;
}

std::function<bool(int32_t, int32_t, int32_t, int32_t, int32_t)> wall_flip_rule(
    const LayerMesh* inner, const LayerMesh* outer, const std::vector<double>& points,
    size_t wall_vertices, bool keep_prisms) {
  if (inner && !keep_prisms) return {};
  const size_t nv = inner ? inner->wall_vertices : wall_vertices;
  const double* wall = inner ? inner->points.data() : points.data();
  return [=](int32_t a, int32_t b, int32_t c, int32_t d, int32_t tag) {
    if (tag != 0) return false;
    for (int32_t v : {a, b, c, d})
      if (v < 0 || size_t(v) >= nv) return false;
    auto at = [&](const double* p, int32_t v) { return p + 3 * size_t(v); };
    if (!wall_flip_ok(at(wall, a), at(wall, b), at(wall, c), at(wall, d))) return false;
    if (inner) {
      const double* front = &inner->points[3 * size_t(inner->layer_vertex(0, inner->layers))];
      if (!wall_flip_ok(at(front, a), at(front, b), at(front, c), at(front, d))) return false;
      if (!layer_flip_ok(*inner, a, b, c, d)) return false;
    }
    return !outer || layer_flip_ok(*outer, a, b, c, d);
  };
}

}  // namespace vm
