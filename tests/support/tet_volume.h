// The volume of one tetrahedron of a volume mesh, for the tests that sum a
// mesh's volume (or a region's) to compare it with the enclosed one.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/mesh/volume_mesh.h"

namespace vm::testing {

/// Six times the signed volume of tetrahedron t of m (positive for a
/// vesselmesh tetrahedron: core/mesh/volume_mesh.h).
inline double tet_volume6(const VolumeMesh& m, size_t t) {
  const int32_t* v = &m.tets[4 * t];
  return vm::tet_volume6(&m.points[3 * size_t(v[0])], &m.points[3 * size_t(v[1])],
                         &m.points[3 * size_t(v[2])], &m.points[3 * size_t(v[3])]);
}

}  // namespace vm::testing
