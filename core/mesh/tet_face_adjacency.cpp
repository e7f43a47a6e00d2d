// Face adjacency of a tetrahedral mesh (tet_face_adjacency.h), in phases:
// every face into the bucket of its smallest vertex (a stable counting
// sort), each bucket sorted by the face's two other vertices, equal runs
// linked.
#include "core/mesh/tet_face_adjacency.h"

#include <algorithm>
#include <string>
#include <utility>

#include "core/mesh/face_elements.h"

namespace vm {
namespace {

/// A face in its smallest vertex's bucket: its two other vertices (sorted)
/// and its code 4 * t + f.
struct BucketFace {
  int32_t mid, hi;
  int32_t code;
};

/// The vertices of face f of the tetrahedron v, sorted.
void sorted_face(const int32_t* v, int f, int32_t out[3]) {
  for (int s = 0, n = 0; s < 4; ++s)
    if (s != f) out[n++] = v[s];
  if (out[0] > out[1]) std::swap(out[0], out[1]);
  if (out[1] > out[2]) std::swap(out[1], out[2]);
  if (out[0] > out[1]) std::swap(out[0], out[1]);
}

}  // namespace

Result<std::vector<int32_t>> tet_face_adjacency(const int32_t* tets, size_t num_tets,
                                                size_t num_vertices) {
  using R = Result<std::vector<int32_t>>;
  const size_t nf = 4 * num_tets;
  for (size_t i = 0; i < nf; ++i)
    if (tets[i] < 0 || size_t(tets[i]) >= num_vertices)
      return R::Error("tetrahedron face adjacency: vertex index out of range (tetrahedron " +
                      std::to_string(i / 4) + ")");
  // Phase 1: bucket sizes (each face goes to its smallest vertex).
  std::vector<uint32_t> start(num_vertices + 1, 0);
  for (size_t t = 0; t < num_tets; ++t) {
    const int32_t* v = &tets[4 * t];
    int32_t f[3];
    for (int k = 0; k < 4; ++k) {
      sorted_face(v, k, f);
      ++start[size_t(f[0]) + 1];
    }
  }
  for (size_t v = 0; v < num_vertices; ++v) start[v + 1] += start[v];
  // Phase 2: the faces scattered into their buckets, in code order.
  std::vector<BucketFace> faces(nf);
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t t = 0; t < num_tets; ++t) {
      const int32_t* v = &tets[4 * t];
      int32_t f[3];
      for (int k = 0; k < 4; ++k) {
        sorted_face(v, k, f);
        faces[fill[size_t(f[0])]++] = {f[1], f[2], int32_t(4 * t) + k};
      }
    }
  }
  // Phase 3: each bucket sorted; runs of equal faces linked.
  std::vector<int32_t> across(nf, kNoTetAcross);
  const auto less = [](const BucketFace& a, const BucketFace& b) {
    if (a.mid != b.mid) return a.mid < b.mid;
    if (a.hi != b.hi) return a.hi < b.hi;
    return a.code < b.code;
  };
  for (size_t v = 0; v < num_vertices; ++v) {
    BucketFace* begin = faces.data() + start[v];
    BucketFace* end = faces.data() + start[v + 1];
    std::sort(begin, end, less);
    for (BucketFace* i = begin; i < end;) {
      BucketFace* j = i + 1;
      while (j < end && j->mid == i->mid && j->hi == i->hi) ++j;
      if (j - i > 2)
        return R::Error(
            "tetrahedron face adjacency: a face shared by more than two tetrahedra "
            "(tetrahedron " +
            std::to_string(i->code >> 2) + ")");
      if (j - i == 2) {
        across[size_t(i[0].code)] = i[1].code;
        across[size_t(i[1].code)] = i[0].code;
      }
      i = j;
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
