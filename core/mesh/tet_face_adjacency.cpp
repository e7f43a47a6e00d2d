// Face adjacency of a tetrahedral mesh (tet_face_adjacency.h): the faces
// grouped by vertex set (group_faces), pairs linked.
#include "core/mesh/tet_face_adjacency.h"

#include <string>

#include "core/mesh/face_elements.h"
#include "core/mesh/face_groups.h"
#include "core/util/default_init_vector.h"

namespace vm {

Result<std::vector<int32_t>> tet_face_adjacency(const int32_t* tets, size_t num_tets,
                                                size_t num_vertices) {
  using R = Result<std::vector<int32_t>>;
  const size_t nf = 4 * num_tets;
  for (size_t i = 0; i < nf; ++i)
    if (tets[i] < 0 || size_t(tets[i]) >= num_vertices)
      return R::Error("tetrahedron face adjacency: vertex index out of range (tetrahedron " +
                      std::to_string(i / 4) + ")");
  // Face f of tetrahedron t is face 4 * t + f of the list: its vertices but f.
  FaceGroups groups;
  {
    DefaultInitVector<int32_t> faces(4 * nf);  // each written once below
    for (size_t t = 0; t < num_tets; ++t) {
      const int32_t* v = &tets[4 * t];
      int32_t* f = &faces[16 * t];
      for (int k = 0; k < 4; ++k, f += 4) {
        for (int s = 0, n = 0; s < 4; ++s)
          if (s != k) f[n++] = v[s];
        f[3] = kNoFourthVertex;
      }
    }
    groups = group_faces(faces.data(), nf, num_vertices);
  }
  std::vector<int32_t> across(nf, kNoTetAcross);
  for (size_t g = 0; g < groups.num_groups(); ++g) {
    const size_t n = groups.size(g);
    const int32_t a = int32_t(groups.face(g, 0));
    if (n > 2)
      return R::Error(
          "tetrahedron face adjacency: a face shared by more than two tetrahedra "
          "(tetrahedron " +
          std::to_string(a >> 2) + ")");
    if (n == 2) {
      const int32_t b = int32_t(groups.face(g, 1));
      across[size_t(a)] = b;
      across[size_t(b)] = a;
    }
  }
  return across;
}

std::vector<int32_t> boundary_face_triangles(const int32_t* tets, size_t num_tets,
                                             const std::vector<int32_t>& across,
                                             const int32_t* triangles, size_t num_triangles) {
  std::vector<int32_t> out(4 * num_tets, -1);
  VolumeMesh m;  // face_elements reads only the elements and faces
  m.tets.assign(tets, tets + 4 * num_tets);
  m.triangles.assign(triangles, triangles + 3 * num_triangles);
  const FaceElements fe = face_elements(m);
  for (size_t k = 0; k < num_triangles; ++k) {
    const int32_t t = fe.element[k];
    if (fe.uses[k] != 1 || t < 0) continue;  // an interface, or no tetrahedron's face
    const int32_t* v = &tets[4 * size_t(t)];
    const int32_t* tri = &triangles[3 * k];
    for (int f = 0; f < 4; ++f) {
      if (v[f] == tri[0] || v[f] == tri[1] || v[f] == tri[2]) continue;
      if (across[4 * size_t(t) + size_t(f)] == kNoTetAcross)
        out[4 * size_t(t) + size_t(f)] = int32_t(k);
    }
  }
  return out;
}

}  // namespace vm
