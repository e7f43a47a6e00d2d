// Faces grouped by vertex set: the one face matcher of the code (the
// tetrahedra's face links, tet_face_adjacency; the elements beside each
// surface face, face_elements; the volume mesh check, check_volume_mesh;
// the OpenFOAM writer's faces, foam_case_files; the faces a region
// submesh keeps, region_submesh). Triangles and quads go in
// one list; each face goes into the bucket of its smallest vertex (a stable
// counting sort), and each bucket is sorted by the face's other vertices, so
// the cost is linear in the number of faces and vertices plus a sort of each
// small bucket.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh/volume_mesh.h"

namespace vm {

/// Slot 3 of a triangle in a face list (a quad fills all four).
inline constexpr int32_t kNoFourthVertex = -1;

/// Faces grouped by vertex set (the result of group_faces).
/// - order: num_faces face indices, group after group.
/// - group_start: num_groups() + 1 offsets into order, increasing: group g
///   is order[group_start[g]] .. order[group_start[g + 1] - 1] (never
///   empty); group_start[0] = 0, group_start.back() = num_faces.
struct FaceGroups {
  std::vector<uint32_t> order;
  std::vector<uint32_t> group_start{0};

  size_t num_groups() const { return group_start.size() - 1; }
  /// How many faces group g holds.
  size_t size(size_t g) const { return group_start[g + 1] - group_start[g]; }
  /// Face k (0 .. size(g) - 1) of group g.
  uint32_t face(size_t g, size_t k) const { return order[group_start[g] + k]; }
};

/// Groups the faces `faces` (4 vertex indices per face, num_faces of them:
/// a quad's 4, a triangle's 3 then kNoFourthVertex; each vertex index in
/// [0, num_vertices); num_faces < 2^32) by their sorted vertex lists (their
/// vertex sets when a face's vertices are distinct; a triangle and a quad
/// are never in one group). Groups come in lexicographic order of their
/// sorted vertex lists, a triangle before the quads whose three smallest
/// vertices are its own (as if its fourth vertex were -1); inside a group,
/// the faces are in input order. The vertices' order within a face (its
/// orientation) is not used.
FaceGroups group_faces(const int32_t* faces, size_t num_faces, size_t num_vertices);

/// The faces of `mesh` as one face list for group_faces (4 slots a face;
/// 4 num_tets() + 5 num_prisms() + num_triangles() + num_quads() faces):
/// first the elements' faces, each as its outward cycle (face_elements.h):
/// face 4 t + k is face k of tetrahedron t (kFaceOut), face 4 num_tets() +
/// 5 p + k is face k of prism p ((0,2,1), (3,4,5), (0,1,4,3), (1,2,5,4),
/// (2,0,3,5)); then the triangles, then the quads, as given. Indices are
/// copied, not checked; a partial element or face at an array's end is left
/// out.
std::vector<int32_t> volume_mesh_faces(const VolumeMesh& mesh);

/// Of face i (< 4 num_tets + 5 num_prisms) of volume_mesh_faces: the element
/// it belongs to, tetrahedra first (0 .. num_tets - 1), then prisms
/// (num_tets + p).
inline size_t face_element(size_t i, size_t num_tets) {
  return i < 4 * num_tets ? i / 4 : num_tets + (i - 4 * num_tets) / 5;
}

}  // namespace vm
