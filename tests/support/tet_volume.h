// The volume of one tetrahedron of a volume mesh, for the tests that sum a
// mesh's volume (or a region's) to compare it with the enclosed one.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/mesh/volume_mesh.h"
#include "core/volume/tet_mesh.h"

namespace vm::testing {

/// Six times the signed volume of tetrahedron t of m (positive for a
/// vesselmesh tetrahedron: core/mesh/volume_mesh.h).
inline double mesh_tet_volume6(const VolumeMesh& m, size_t t) {
  const int32_t* v = &m.tets[4 * t];
  return tet_volume6(&m.points[3 * size_t(v[0])], &m.points[3 * size_t(v[1])],
                     &m.points[3 * size_t(v[2])], &m.points[3 * size_t(v[3])]);
}

/// The volume of a tetrahedralisation in progress: the sum over its live
/// tetrahedra.
inline double total_volume(const TetMesh& m) {
  double v = 0;
  const auto t = m.tets();
  for (size_t i = 0; i < t.size(); i += 4)
    v += tet_volume6(m.point(t[i]), m.point(t[i + 1]), m.point(t[i + 2]), m.point(t[i + 3])) / 6;
  return v;
}

}  // namespace vm::testing
