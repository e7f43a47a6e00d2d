// The face adjacency of a tetrahedral mesh: for every face of every
// tetrahedron, the tetrahedron across it (TetMesh::from_arrays, the page's
// clipped view through the WebAssembly binding). Faces are matched on their
// vertex sets by the one face matcher, group_faces (core/mesh/face_groups.h),
// so the cost is linear in the number of faces plus a sort of each small
// bucket.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh/volume_mesh.h"
#include "core/util/result.h"

namespace vm {

/// Entry of a face no other tetrahedron has (a boundary face).
inline constexpr int32_t kNoTetAcross = -1;

/// Face links of the tetrahedral mesh `tets` (4 vertex indices per
/// tetrahedron, num_tets of them, each index in [0, num_vertices); four
/// distinct vertices per tetrahedron; orientation is not used).
/// Returns `across`, 4 * num_tets entries: face f of tetrahedron t is the
/// face opposite its vertex f (kFaceOut of core/mesh/volume_mesh.h), and
///   across[4 * t + f] = 4 * u + g   when face g of tetrahedron u (u != t)
///                                   has the same vertex set (u = across >> 2
///                                   is the tetrahedron across, g = across & 3
///                                   the face's index in u; then
///                                   across[4 * u + g] = 4 * t + f),
///   across[4 * t + f] = kNoTetAcross when no other tetrahedron has it.
/// Errors: an index out of range, a face of more than two tetrahedra.
Result<std::vector<int32_t>> tet_face_adjacency(const int32_t* tets, size_t num_tets,
                                                size_t num_vertices);

/// The surface triangle on each boundary face: 4 * num_tets entries (tets
/// and across as for tet_face_adjacency; triangles: 3 vertex indices per
/// triangle, num_triangles of them, in any orientation): entry 4 * t + f is
/// the triangle with the vertex set of face f of t when across[4 * t + f] is
/// kNoTetAcross and one exists (the last such triangle), else -1.
/// Triangles on faces between two tetrahedra (interfaces) are ignored.
/// Matches through face_elements() (core/mesh/face_elements.h).
std::vector<int32_t> boundary_face_triangles(const int32_t* tets, size_t num_tets,
                                             const std::vector<int32_t>& across,
                                             const int32_t* triangles, size_t num_triangles);

}  // namespace vm
