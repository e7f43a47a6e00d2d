// Small generated surfaces for unit tests (no external data).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "core/io/stl.h"
#include "core/mesh/surface_mesh.h"

namespace vm::testing {

/// Regular tetrahedron-like closed surface: 4 vertices, 4 outward triangles.
inline SurfaceMesh tetrahedron() {
  SurfaceMesh m;
  m.points = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  m.triangles = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  return m;
}

// An n x n grid of squares on [0, 1]^2 at z = 0, two triangles each,
// counterclockwise seen from +z.
inline SurfaceMesh square_grid(int n) {
  SurfaceMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.points.insert(m.points.end(), {double(i) / n, double(j) / n, 0});
  auto id = [&](int i, int j) { return int32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.insert(m.triangles.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

/// Open cylinder (tube) of radius r, length len along z, n around, m along;
/// outward oriented, 2 boundary loops.
inline SurfaceMesh open_tube(int n, int m, double r = 1.0, double len = 4.0) {
  SurfaceMesh s;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i < n; ++i) {
      double a = 2 * std::numbers::pi * i / n;
      s.points.insert(s.points.end(), {r * std::cos(a), r * std::sin(a), len * j / m});
    }
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      int32_t a = j * n + i, b = j * n + (i + 1) % n, c = a + n, d = b + n;
      s.triangles.insert(s.triangles.end(), {a, b, d, a, d, c});
    }
  return s;
}

/// open_tube(n, m, r, len) closed by two flat fans (centers appended last):
/// a closed cylinder with sharp 90-degree rims, outward oriented.
inline SurfaceMesh capped_tube(int n, int m, double r = 1.0, double len = 4.0) {
  SurfaceMesh s = open_tube(n, m, r, len);
  const int32_t bottom = int32_t(s.num_vertices()), top = bottom + 1;
  s.points.insert(s.points.end(), {0, 0, 0, 0, 0, len});
  for (int i = 0; i < n; ++i) {
    const int32_t a = i, b = (i + 1) % n;
    s.triangles.insert(s.triangles.end(), {b, a, bottom});
    s.triangles.insert(s.triangles.end(), {m * n + a, m * n + b, top});
  }
  return s;
}

/// Torus with n x m quads split in two, outward oriented: genus 1, closed.
inline SurfaceMesh torus(int n, int m, double R = 3.0, double r = 1.0) {
  SurfaceMesh s;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      double u = 2 * std::numbers::pi * i / n, v = 2 * std::numbers::pi * j / m;
      s.points.insert(s.points.end(), {(R + r * std::cos(v)) * std::cos(u),
                                       (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      int32_t a = j * n + i, b = j * n + (i + 1) % n;
      int32_t c = ((j + 1) % m) * n + i, d = ((j + 1) % m) * n + (i + 1) % n;
      s.triangles.insert(s.triangles.end(), {a, b, d, a, d, c});
    }
  return s;
}

/// ASCII STL text of a surface (one facet per triangle), every coordinate
/// with 17 significant digits (it reads back as the same double).
/// The triangles of `a` and of `b` as one surface (b's vertices after a's).
inline SurfaceMesh joined(SurfaceMesh a, const SurfaceMesh& b) {
  const int32_t base = int32_t(a.num_vertices());
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  for (int32_t v : b.triangles) a.triangles.push_back(base + v);
  return a;
}

inline std::string ascii_stl(const SurfaceMesh& m, const std::string& name = "t") {
  std::string s = "solid " + name + "\n";
  char buf[128];
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    s += "  facet normal 0 0 0\n    outer loop\n";
    for (int k = 0; k < 3; ++k) {
      const double* p = &m.points[3 * m.triangles[3 * t + k]];
      std::snprintf(buf, sizeof(buf), "      vertex %.17g %.17g %.17g\n", p[0], p[1], p[2]);
      s += buf;
    }
    s += "    endloop\n  endfacet\n";
  }
  return s + "endsolid " + name + "\n";
}

inline std::vector<uint8_t> bytes_of(const std::string& s) {
  return std::vector<uint8_t>(s.begin(), s.end());
}

/// Reverses the orientation of triangle t.
inline void flip_triangle(SurfaceMesh& m, size_t t) {
  std::swap(m.triangles[3 * t + 1], m.triangles[3 * t + 2]);
}

/// Median of `v` (upper median for an even count).
inline double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace vm::testing
