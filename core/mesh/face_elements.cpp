// Face -> element incidence: the elements' faces and the mesh's triangles
// and quads in one face list, grouped by vertex set (group_faces); in each
// group, the elements' faces come first and every surface face takes its
// element from them.
#include "core/mesh/face_elements.h"

#include <algorithm>

#include "core/mesh/face_groups.h"

namespace vm {
namespace {

/// True when the n-cycle g is the n-cycle f read from another start (same
/// orientation). Precondition: same vertex set.
bool same_cycle(const int32_t* f, const int32_t* g, int n) {
  int s = 0;
  while (s < n && g[s] != f[0]) ++s;
  if (s == n) return false;
  for (int k = 1; k < n; ++k)
    if (g[(s + k) % n] != f[k]) return false;
  return true;
}

/// Calls fn(v) on every vertex index of the elements and faces of `m` (a
/// VolumeMesh, const or not), whole elements and faces only.
template <class Mesh, class Fn>
void for_each_index(Mesh& m, Fn fn) {
  const auto each = [&](auto& a, size_t n) {
    for (size_t i = 0; i < n; ++i) fn(a[i]);
  };
  each(m.tets, 4 * m.num_tets());
  each(m.prisms, 6 * m.num_prisms());
  each(m.triangles, 3 * m.num_triangles());
  each(m.quads, 4 * m.num_quads());
}

/// A copy of the elements and faces of `mesh` with every vertex index
/// replaced by its rank among the distinct indices used: equal faces stay
/// equal, and the indices are in [0, the number of distinct indices).
VolumeMesh ranked_indices(const VolumeMesh& mesh) {
  std::vector<int32_t> used;
  for_each_index(mesh, [&](int32_t v) { used.push_back(v); });
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  VolumeMesh m;
  m.tets = mesh.tets;
  m.prisms = mesh.prisms;
  m.triangles = mesh.triangles;
  m.quads = mesh.quads;
  for_each_index(m, [&](int32_t& v) {
    v = int32_t(std::lower_bound(used.begin(), used.end(), v) - used.begin());
  });
  return m;
}

}  // namespace

FaceElements face_elements(const VolumeMesh& mesh) {
  const size_t nt = mesh.num_triangles(), nq = mesh.num_quads(), nf = nt + nq;
  const size_t ne = 4 * mesh.num_tets() + 5 * mesh.num_prisms();  // the elements' faces
  FaceElements r;
  r.uses.assign(nf, 0);
  r.element.assign(nf, -1);
  // The indices as they are when all are in [0, max(vertices, indices)],
  // else ranked (any int32 is allowed).
  int32_t lo = 0, hi = 0;
  size_t count = 0;
  for_each_index(mesh, [&](int32_t v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    ++count;
  });
  const bool direct = lo >= 0 && size_t(hi) <= std::max(mesh.num_vertices(), count);
  const std::vector<int32_t> faces = volume_mesh_faces(direct ? mesh : ranked_indices(mesh));
  const FaceGroups groups =
      group_faces(faces.data(), faces.size() / 4, direct ? size_t(hi) + 1 : count);
  for (size_t g = 0; g < groups.num_groups(); ++g) {
    const size_t n = groups.size(g);
    size_t elements = 0;  // the group's elements' faces, first in it
    while (elements < n && groups.face(g, elements) < ne) ++elements;
    for (size_t k = elements; k < n; ++k) {
      const size_t s = groups.face(g, k);
      const int32_t* f = &faces[4 * s];
      const int nv = f[3] == kNoFourthVertex ? 3 : 4;
      uint8_t& uses = r.uses[s - ne];
      int32_t& element = r.element[s - ne];
      uses = uint8_t(std::min<size_t>(elements, 255));
      for (size_t j = 0; j < elements; ++j) {
        const size_t e = groups.face(g, j);
        if (same_cycle(f, &faces[4 * e], nv) || element < 0)
          element = int32_t(face_element(e, mesh.num_tets()));
      }
    }
  }
  return r;
}

}  // namespace vm
