// Face -> element incidence: the mesh's triangles and quads go into a hash
// table keyed by their sorted vertices; every element face is looked up.
#include "core/mesh/face_elements.h"

#include <algorithm>
#include <array>

#include "core/util/index_hash_table.h"

namespace vm {
namespace {

using Key = std::array<int32_t, 4>;  // sorted vertices, -1 after a triangle's 3

Key key_of(const int32_t* f, int n) {
  Key k{-1, -1, -1, -1};
  std::copy(f, f + n, k.begin());
  std::sort(k.begin(), k.begin() + n);
  return k;
}

uint64_t hash_of(const Key& k) {
  uint64_t h = 0;
  for (int32_t v : k) h = (h ^ uint32_t(v)) * 0x100000001b3ULL;
  return h;
}

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

}  // namespace

FaceElements face_elements(const VolumeMesh& mesh) {
  const size_t nt = mesh.num_triangles(), nq = mesh.num_quads(), nf = nt + nq;
  FaceElements r;
  r.uses.assign(nf, 0);
  r.element.assign(nf, -1);
  std::vector<Key> keys(nf);
  auto face = [&](size_t f) { return f < nt ? &mesh.triangles[3 * f] : &mesh.quads[4 * (f - nt)]; };
  IndexHashTable table(nf);
  for (size_t f = 0; f < nf; ++f) {
    keys[f] = key_of(face(f), f < nt ? 3 : 4);
    // Every face is stored, equal ones too (each gets its own answer).
    table.find_or_insert(hash_of(keys[f]), int32_t(f), [](int32_t) { return false; });
  }
  // Every face of the mesh equal to the element face g (n vertices).
  auto visit = [&](const int32_t* g, int n, int32_t element) {
    const Key k = key_of(g, n);
    table.for_each_with_hash(hash_of(k), [&](int32_t s) {
      if (keys[s] != k) return;
      if (r.uses[s] < 255) ++r.uses[s];
      if (same_cycle(face(size_t(s)), g, n) || r.element[s] < 0) r.element[s] = element;
    });
  };
  for (size_t e = 0; e < mesh.num_tets(); ++e) {
    const int32_t* t = &mesh.tets[4 * e];
    for (const auto& f : kFaceOut) {
      const int32_t g[3] = {t[f[0]], t[f[1]], t[f[2]]};
      visit(g, 3, int32_t(e));
    }
  }
  for (size_t e = 0; e < mesh.num_prisms(); ++e) {
    const int32_t* p = &mesh.prisms[6 * e];
    const int32_t element = int32_t(mesh.num_tets() + e);
    const int32_t bottom[3] = {p[0], p[2], p[1]}, top[3] = {p[3], p[4], p[5]};
    const int32_t q0[4] = {p[0], p[1], p[4], p[3]}, q1[4] = {p[1], p[2], p[5], p[4]},
                  q2[4] = {p[2], p[0], p[3], p[5]};
    visit(bottom, 3, element);
    visit(top, 3, element);
    for (const int32_t* q : {q0, q1, q2}) visit(q, 4, element);
  }
  return r;
}

}  // namespace vm
