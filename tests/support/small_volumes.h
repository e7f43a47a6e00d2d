// Small generated volume meshes (tetrahedra, prisms, tagged boundary and
// interface faces) for the writers' tests.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "core/mesh/volume_mesh.h"

namespace vm::testing {

/// The cube [0, n]^3 as n^3 unit cubes, each split into the 6 tetrahedra
/// around its main diagonal (the same in every cube, so they conform), all
/// positive, region 0. Boundary triangles outward, tagged by the cube's face
/// they lie on: 0 x=0, 1 x=n, 2 y=0, 3 y=n, 4 z=0, 5 z=n.
inline VolumeMesh cube_tets(int n) {
  VolumeMesh m;
  auto id = [&](int i, int j, int k) { return int32_t((k * (n + 1) + j) * (n + 1) + i); };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        m.points.insert(m.points.end(), {double(i), double(j), double(k)});
  static constexpr int kAxes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                      {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& axes : kAxes) {
          int c[3] = {i, j, k};
          int32_t t[4];
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[axes[s]];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          if (tet_volume6(&m.points[3 * t[0]], &m.points[3 * t[1]], &m.points[3 * t[2]],
                          &m.points[3 * t[3]]) < 0)
            std::swap(t[1], t[2]);
          m.tets.insert(m.tets.end(), t, t + 4);
          m.tet_region.push_back(0);
        }
  for (size_t e = 0; e < m.num_tets(); ++e)
    for (const auto& f : kFaceOut) {
      const int32_t g[3] = {m.tets[4 * e + f[0]], m.tets[4 * e + f[1]], m.tets[4 * e + f[2]]};
      for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
          const double plane = side * n;
          if (m.points[3 * g[0] + axis] == plane && m.points[3 * g[1] + axis] == plane &&
              m.points[3 * g[2] + axis] == plane) {
            m.triangles.insert(m.triangles.end(), g, g + 3);
            m.triangle_tag.push_back(2 * axis + side);
          }
        }
    }
  return m;
}

/// Splits cube_tets(n)'s tetrahedra into region 0 (the first half) and
/// region 1, and adds the faces between them as triangles tagged
/// `interface_tag`, oriented outward of region 0.
inline void split_regions(VolumeMesh& m, int32_t interface_tag) {
  const size_t half = m.num_tets() / 2;
  for (size_t e = 0; e < m.num_tets(); ++e) m.tet_region[e] = e < half ? 0 : 1;
  std::map<std::array<int32_t, 3>, std::pair<size_t, std::array<int32_t, 3>>> faces;
  for (size_t e = 0; e < m.num_tets(); ++e)
    for (const auto& f : kFaceOut) {
      std::array<int32_t, 3> g = {m.tets[4 * e + f[0]], m.tets[4 * e + f[1]], m.tets[4 * e + f[2]]};
      std::array<int32_t, 3> key = g;
      std::sort(key.begin(), key.end());
      auto [it, inserted] = faces.insert({key, {e, g}});
      if (inserted) continue;
      const size_t other = it->second.first;
      if (m.tet_region[other] == m.tet_region[e]) continue;
      const auto& outward_of_0 = m.tet_region[other] == 0 ? it->second.second : g;
      m.triangles.insert(m.triangles.end(), outward_of_0.begin(), outward_of_0.end());
      m.triangle_tag.push_back(interface_tag);
    }
}

/// Two regions: region 1 = 2 prisms (the unit square's two triangles
/// extruded from z = 0 to z = 1), region 0 = 2 tetrahedra on the top
/// square up to an apex at z = 2. Faces: tag 0 the prisms' bottom (2
/// triangles), tag 1 their sides (4 quads), tag 2 the tetrahedra's sides (4
/// triangles), tag 3 the interface z = 1 (2 triangles, outward of the
/// tetrahedra's region 0, i.e. facing down).
inline VolumeMesh prism_tet_stack() {
  VolumeMesh m;
  m.points = {0,   0,   0, 1, 0, 0, 1, 1, 0, 0, 1, 0,  // bottom square 0-3
              0,   0,   1, 1, 0, 1, 1, 1, 1, 0, 1, 1,  // top square 4-7
              0.5, 0.5, 2};                            // apex 8
  // Bottom triangles counterclockwise seen from the top (+z).
  m.prisms = {0, 1, 2, 4, 5, 6, 0, 2, 3, 4, 6, 7};
  m.prism_region = {1, 1};
  m.tets = {4, 5, 6, 8, 4, 6, 7, 8};
  m.tet_region = {0, 0};
  m.triangles = {0, 2, 1, 0, 3, 2,                    // bottom, facing -z
                 4, 5, 8, 5, 6, 8, 6, 7, 8, 7, 4, 8,  // tetrahedra's sides
                 4, 6, 5, 4, 7, 6};                   // interface, facing -z
  m.triangle_tag = {0, 0, 2, 2, 2, 2, 3, 3};
  m.quads = {0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7};
  m.quad_tag = {1, 1, 1, 1};
  return m;
}

}  // namespace vm::testing
