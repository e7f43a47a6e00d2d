// The volume elements on either side of each surface triangle and quad of a
// volume mesh: tells the domain's exterior boundary from interfaces between
// regions, and gives each face the element it bounds (svFSI's
// GlobalElementID of a face).
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh/volume_mesh.h"

namespace vm {

/// Per face of the mesh, triangles first then quads (num_triangles() +
/// num_quads() entries):
/// - uses: how many elements have the face (by vertex set): 1 on the
///   exterior boundary, 2 on an interface, 0 for a face of no element
///   (capped at 255).
/// - element: the element the face is oriented outward of (its face read
///   in the same cyclic order), else the first element having it, -1 when
///   none. Elements are numbered tetrahedra first (0 .. num_tets()-1), then
///   prisms (num_tets() + p), the order write_vtu numbers its cells in.
struct FaceElements {
  std::vector<uint8_t> uses;
  std::vector<int32_t> element;
};

/// Outward faces of the elements: tetrahedron (0,1,2,3): (1,2,3), (0,3,2),
/// (0,1,3), (0,2,1); prism: (0,2,1), (3,4,5), (0,1,4,3), (1,2,5,4),
/// (2,0,3,5). The element faces and the mesh's faces are grouped by vertex
/// set in one list (group_faces, core/mesh/face_groups.h). Vertex indices
/// are only compared (no range precondition); a partial element or face at
/// an array's end is ignored.
FaceElements face_elements(const VolumeMesh& mesh);

}  // namespace vm
