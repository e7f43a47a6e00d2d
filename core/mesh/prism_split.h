// Splitting a prism into three tetrahedra by the global-vertex-index rule
// (Dompierre, Labbe, Vallet and Camarero, "How to subdivide pyramids, prisms
// and hexahedra into tetrahedra", IMR 1999): each quadrilateral face is cut
// by the diagonal from its smallest vertex index, so two prisms sharing a
// face cut it the same way and the split mesh stays conforming (seed
// Marchandise et al., section 2.2: boundary-layer prisms split into
// tetrahedra).
#pragma once

#include <array>
#include <cstdint>

namespace vm {

/// The three tetrahedra of prism v (6 vertex ids: 0-1-2 bottom, 3-4-5 top,
/// 3 above 0, as VolumeMesh), each as 4 vertex ids in an order that is
/// positive whenever the prism is (the rotations used keep orientation).
/// Precondition: the six ids are distinct.
std::array<std::array<int32_t, 4>, 3> split_prism(const int32_t v[6]);

/// The two triangles of quad q (4 vertex ids, a cycle) cut by the diagonal
/// from its smallest id, as split_prism cuts the prisms' side faces, in the
/// quad's orientation.
std::array<std::array<int32_t, 3>, 2> split_quad(const int32_t q[4]);

}  // namespace vm
