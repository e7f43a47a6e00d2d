// Sphere surfaces for tests: a subdivided icosahedron projected on a sphere.
#pragma once

#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

#include "core/mesh/surface_mesh.h"

namespace vm::testing {

/// Closed, outward-oriented sphere of radius r centered at (cx, cy, cz):
/// the icosahedron with each triangle split in 4, `levels` times
/// (20 * 4^levels triangles), vertices on the sphere.
inline SurfaceMesh icosphere(int levels, double r = 1.0, double cx = 0, double cy = 0,
                             double cz = 0) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  SurfaceMesh s;
  s.points = {-1, g,  0,  1, g, 0,  -1, -g, 0,  1, -g, 0, 0,  -1, g,  0,  1, g,
              0,  -1, -g, 0, 1, -g, g,  0,  -1, g, 0,  1, -g, 0,  -1, -g, 0, 1};
  s.triangles = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                 6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int32_t, int32_t>, int32_t> mid;
    auto midpoint = [&](int32_t a, int32_t b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      const int32_t v = int32_t(s.num_vertices());
      for (int k = 0; k < 3; ++k)
        s.points.push_back(0.5 * (s.points[3 * size_t(a) + k] + s.points[3 * size_t(b) + k]));
      mid[key] = v;
      return v;
    };
    std::vector<int32_t> next;
    for (size_t t = 0; t < s.num_triangles(); ++t) {
      const int32_t a = s.triangles[3 * t], b = s.triangles[3 * t + 1], c = s.triangles[3 * t + 2];
      const int32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    s.triangles = std::move(next);
  }
  for (size_t v = 0; v < s.num_vertices(); ++v) {
    double* p = &s.points[3 * v];
    const double len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    p[0] = cx + r * p[0] / len;
    p[1] = cy + r * p[1] / len;
    p[2] = cz + r * p[2] / len;
  }
  return s;
}

}  // namespace vm::testing
