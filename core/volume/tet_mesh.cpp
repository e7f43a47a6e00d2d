// Mutable region mesh for local reconnection and smoothing (Shewchuk 2002;
// Klingner and Shewchuk 2007); see tet_mesh.h for the layout.
#include "core/volume/tet_mesh.h"

#include <algorithm>
#include <string>

#include "core/geom/predicates.h"
#include "core/volume/delaunay3d.h"

namespace vm {
namespace {

inline int slot_of(const int32_t* v, int32_t x) {
  for (int k = 0; k < 4; ++k)
    if (v[k] == x) return k;
  return -1;
}

inline bool parity_even(int a, int b, int c, int d) {
  int p[4] = {a, b, c, d}, inv = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inv += p[i] > p[j];
  return inv % 2 == 0;
}

// Equality of face keys without memcmp (the hot loop of replace()).
inline bool same_key(const std::array<int32_t, 3>& a, const std::array<int32_t, 3>& b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

inline std::array<int32_t, 3> face_key(const int32_t* v, int k) {
  std::array<int32_t, 3> f;
  for (int s = 0, n = 0; s < 4; ++s)
    if (s != k) f[size_t(n++)] = v[s];
  if (f[0] > f[1]) std::swap(f[0], f[1]);
  if (f[1] > f[2]) std::swap(f[1], f[2]);
  if (f[0] > f[1]) std::swap(f[0], f[1]);
  return f;
}

}  // namespace

Result<TetMesh> TetMesh::from_kernel(const Delaunay3D& kernel, int32_t tag,
                                     const std::vector<int32_t>& vertex_map, int32_t num_vertices,
                                     std::vector<uint8_t> fixed) {
  using R = Result<TetMesh>;
  if (vertex_map.size() != kernel.num_vertices())
    return R::Error("tet mesh: one vertex_map entry per kernel vertex expected");
  if (num_vertices < 0 || fixed.size() != size_t(num_vertices))
    return R::Error("tet mesh: one fixed flag per vertex expected");
  TetMesh m;
  m.pts_.assign(3 * size_t(num_vertices), 0.0);
  std::vector<uint8_t> seen(size_t(num_vertices), 0);
  for (size_t v = 0; v < vertex_map.size(); ++v) {
    const int32_t w = vertex_map[v];
    if (w < 0) continue;
    if (w >= num_vertices) return R::Error("tet mesh: vertex_map entry out of range");
    for (int k = 0; k < 3; ++k) m.pts_[3 * size_t(w) + size_t(k)] = kernel.point(int32_t(v))[k];
    seen[size_t(w)] = 1;
  }
  m.fixed_ = std::move(fixed);
  m.vtet_.assign(size_t(num_vertices), -1);
  // Phase 1: ids of the region's tetrahedra, ordered by their smallest
  // mesh vertex (a counting sort: with vertices numbered along a curve,
  // neighbors get nearby ids, which keeps the optimizer's memory accesses
  // local); ties in kernel id order.
  const int32_t cap = int32_t(kernel.tet_capacity());
  std::vector<int32_t> id(size_t(cap), -1);
  std::vector<int32_t> first(size_t(num_vertices) + 1, 0);
  for (int32_t t = 0; t < cap; ++t) {
    if (!kernel.is_live(t) || kernel.is_ghost(t) || kernel.tag(t) != tag) continue;
    int32_t lo = INT32_MAX;
    for (int k = 0; k < 4; ++k) {
      const int32_t w = vertex_map[size_t(kernel.tet(t)[k])];
      if (w < 0) return R::Error("tet mesh: a region vertex is not mapped");
      lo = std::min(lo, w);
    }
    id[size_t(t)] = lo;
    ++first[size_t(lo) + 1];
  }
  for (size_t v = 0; v < size_t(num_vertices); ++v) first[v + 1] += first[v];
  const int32_t n = first[size_t(num_vertices)];
  for (int32_t t = 0; t < cap; ++t)
    if (id[size_t(t)] >= 0) id[size_t(t)] = first[size_t(id[size_t(t)])]++;
  m.tv_.resize(4 * size_t(n));
  m.tn_.resize(4 * size_t(n));
  m.tc_.assign(size_t(n), 0);
  // Phase 2: vertices, neighbors and constraints (slots kept, so the
  // kernel's face indices stay valid).
  for (int32_t t = 0; t < cap; ++t) {
    const int32_t i = id[size_t(t)];
    if (i < 0) continue;
    for (int k = 0; k < 4; ++k) {
      const int32_t w = vertex_map[size_t(kernel.tet(t)[k])];
      m.tv_[4 * size_t(i) + size_t(k)] = w;
      m.vtet_[size_t(w)] = i;
      const int32_t e = kernel.neighbor(t, k);
      const int32_t u = id[size_t(e >> 2)];
      m.tn_[4 * size_t(i) + size_t(k)] = u >= 0 ? 4 * u + (e & 3) : kBoundary;
      if (u >= 0 && kernel.is_constrained(t, k)) m.tc_[size_t(i)] |= uint8_t(1u << k);
    }
  }
  m.stamp_.assign(size_t(n), 0);
  return m;
}

Result<TetMesh> TetMesh::from_arrays(std::vector<double> points, const std::vector<int32_t>& tets,
                                     std::vector<uint8_t> fixed) {
  using R = Result<TetMesh>;
  if (points.size() % 3 != 0 || tets.size() % 4 != 0)
    return R::Error("tet mesh: array sizes not multiples of 3 / 4");
  const size_t nv = points.size() / 3;
  if (fixed.size() != nv) return R::Error("tet mesh: one fixed flag per vertex expected");
  for (int32_t v : tets)
    if (v < 0 || size_t(v) >= nv) return R::Error("tet mesh: vertex index out of range");
  TetMesh m;
  m.pts_ = std::move(points);
  m.fixed_ = std::move(fixed);
  m.vtet_.assign(nv, -1);
  m.tv_ = tets;
  m.tn_.assign(tets.size(), kBoundary);
  m.tc_.assign(tets.size() / 4, 0);
  m.stamp_.assign(tets.size() / 4, 0);
  for (size_t i = 0; i < tets.size(); ++i) m.vtet_[size_t(tets[i])] = int32_t(i / 4);
  // Faces matched by sorting their keys.
  struct F {
    std::array<int32_t, 3> key;
    int32_t code;
  };
  std::vector<F> faces(tets.size());
  for (size_t t = 0; t < tets.size() / 4; ++t)
    for (int k = 0; k < 4; ++k)
      faces[4 * t + size_t(k)] = {face_key(&tets[4 * t], k), int32_t(4 * t) + k};
  std::sort(faces.begin(), faces.end(), [](const F& a, const F& b) {
    return a.key < b.key || (a.key == b.key && a.code < b.code);
  });
  for (size_t i = 0; i < faces.size();) {
    size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i > 2) return R::Error("tet mesh: a face shared by more than two tetrahedra");
    if (j - i == 2) {
      m.tn_[size_t(faces[i].code)] = faces[i + 1].code;
      m.tn_[size_t(faces[i + 1].code)] = faces[i].code;
    }
    i = j;
  }
  return m;
}

int32_t TetMesh::add_vertex(const double* p) {
  pts_.insert(pts_.end(), {p[0], p[1], p[2]});
  fixed_.push_back(0);
  vtet_.push_back(-1);
  return int32_t(vtet_.size() - 1);
}

int32_t TetMesh::new_slot() {
  if (!free_.empty()) {
    const int32_t t = free_.back();
    free_.pop_back();
    return t;
  }
  const int32_t t = int32_t(tc_.size());
  tv_.insert(tv_.end(), {-1, -1, -1, -1});
  tn_.insert(tn_.end(), {kBoundary, kBoundary, kBoundary, kBoundary});
  tc_.push_back(0);
  stamp_.push_back(0);
  return t;
}

void TetMesh::star(int32_t v, std::vector<int32_t>& out) const {
  out.clear();
  const int32_t t0 = vtet_[size_t(v)];
  if (t0 < 0) return;
  if (gen_ == 0xffffffffu) {
    std::fill(stamp_.begin(), stamp_.end(), 0);
    gen_ = 0;
  }
  const uint32_t mark = ++gen_;
  out.push_back(t0);
  stamp_[size_t(t0)] = mark;
  for (size_t i = 0; i < out.size(); ++i) {
    const int32_t t = out[i];
    const int32_t* tv = &tv_[4 * size_t(t)];
    for (int k = 0; k < 4; ++k) {
      if (tv[k] == v) continue;
      const int32_t e = tn_[4 * size_t(t) + size_t(k)];
      if (e < 0) continue;
      const int32_t u = e >> 2;
      if (stamp_[size_t(u)] == mark) continue;
      stamp_[size_t(u)] = mark;
      out.push_back(u);
    }
  }
}

bool TetMesh::edge_ring(int32_t t, int32_t a, int32_t b, std::vector<int32_t>& ring_tets,
                        std::vector<int32_t>& ring, int max_size) const {
  ring_tets.clear();
  ring.clear();
  const int32_t* v = tet(t);
  const int sa = slot_of(v, a), sb = slot_of(v, b);
  int sc = -1, sd = -1;
  for (int s = 0; s < 4; ++s)
    if (s != sa && s != sb) (sc < 0 ? sc : sd) = s;
  if (!parity_even(sa, sb, sc, sd)) std::swap(sc, sd);
  int32_t c = v[sc], d = v[sd];
  int32_t cur = t;
  int k = sc;  // slot of c in cur
  for (int n = 0; n < max_size; ++n) {
    ring_tets.push_back(cur);
    ring.push_back(c);
    // Next: across the face (a, b, d), opposite c.
    const int32_t e = tn_[4 * size_t(cur) + size_t(k)];
    if (e < 0 || ((tc_[size_t(cur)] >> k) & 1)) return false;
    cur = e >> 2;
    if (cur == t) return true;
    // In cur, the face (a, b, d) is opposite slot e & 3: that vertex is the
    // next d, and d becomes the vertex to cross.
    const int32_t* w = tet(cur);
    k = 0;
    while (w[k] != d) ++k;
    c = d;
    d = w[e & 3];
  }
  return false;  // more than max_size tetrahedra around the edge
}

bool TetMesh::replace(const int32_t* old_tets, int n_old, const std::array<int32_t, 4>* new_tets,
                      int n_new, std::vector<int32_t>* new_ids) {
  auto in_old = [&](int32_t u) {
    for (int i = 0; i < n_old; ++i)
      if (old_tets[i] == u) return true;
    return false;
  };
  // Phase 1: outer faces of the old set.
  outer_.clear();
  for (int i = 0; i < n_old; ++i) {
    const int32_t t = old_tets[i];
    for (int k = 0; k < 4; ++k) {
      const int32_t e = tn_[4 * size_t(t) + size_t(k)];
      if (e >= 0 && in_old(e >> 2)) {
        if ((tc_[size_t(t)] >> k) & 1) return false;
        continue;
      }
      outer_.push_back({face_key(tet(t), k), e, uint8_t((tc_[size_t(t)] >> k) & 1), 0});
    }
  }
  // Phase 2: match the faces of the new set (keys computed once).
  match_.assign(4 * size_t(n_new), -1);  // outer index, or -2 - (4 i + k)
  new_keys_.resize(4 * size_t(n_new));
  for (int i = 0; i < n_new; ++i)
    for (int k = 0; k < 4; ++k)
      new_keys_[4 * size_t(i) + size_t(k)] = face_key(new_tets[i].data(), k);
  for (int f = 0; f < 4 * n_new; ++f) {
    if (match_[size_t(f)] != -1) continue;
    const auto& key = new_keys_[size_t(f)];
    int32_t found = -1;
    for (size_t o = 0; o < outer_.size() && found < 0; ++o)
      if (!outer_[o].used && same_key(outer_[o].key, key)) found = int32_t(o);
    if (found >= 0) {
      outer_[size_t(found)].used = 1;
      match_[size_t(f)] = found;
      continue;
    }
    for (int g = 4 * (f / 4 + 1); g < 4 * n_new && found < 0; ++g)
      if (match_[size_t(g)] == -1 && same_key(new_keys_[size_t(g)], key)) {
        found = g;
        match_[size_t(g)] = -2 - f;
        match_[size_t(f)] = -2 - g;
      }
    if (found < 0) return false;
  }
  for (const OuterFace& f : outer_)
    if (!f.used) return false;
  // Phase 3: commit (old slots reused first).
  for (int i = 0; i < n_old; ++i)
    for (int s = 0; s < 4; ++s) vtet_[size_t(tet(old_tets[i])[s])] = -1;
  int32_t ids_local[64];
  std::vector<int32_t> ids_heap;
  int32_t* ids = ids_local;
  if (n_new > 64) {
    ids_heap.resize(size_t(n_new));
    ids = ids_heap.data();
  }
  for (int i = 0; i < n_new; ++i) ids[i] = i < n_old ? old_tets[i] : new_slot();
  for (int i = n_new; i < n_old; ++i) {
    tv_[4 * size_t(old_tets[i])] = -1;
    tc_[size_t(old_tets[i])] = 0;
    free_.push_back(old_tets[i]);
  }
  for (int i = 0; i < n_new; ++i) {
    const int32_t t = ids[i];
    std::copy(new_tets[i].begin(), new_tets[i].end(), &tv_[4 * size_t(t)]);
    tc_[size_t(t)] = 0;
    for (int32_t x : new_tets[i]) vtet_[size_t(x)] = t;
  }
  for (int i = 0; i < n_new; ++i)
    for (int k = 0; k < 4; ++k) {
      const int32_t m = match_[4 * size_t(i) + size_t(k)];
      const int32_t e = 4 * ids[i] + k;
      if (m >= 0) {
        const OuterFace& f = outer_[size_t(m)];
        tn_[size_t(e)] = f.link;
        if (f.link >= 0) tn_[size_t(f.link)] = e;
        tc_[size_t(ids[i])] |= uint8_t(f.constrained << k);
      } else {
        const int32_t other = -2 - m;
        tn_[size_t(e)] = 4 * ids[other / 4] + other % 4;
      }
    }
  if (new_ids) new_ids->assign(ids, ids + n_new);
  return true;
}

std::vector<int32_t> TetMesh::tets() const {
  std::vector<int32_t> out;
  out.reserve(4 * num_tets());
  for (size_t t = 0; t < capacity(); ++t)
    if (tv_[4 * t] >= 0) out.insert(out.end(), &tv_[4 * t], &tv_[4 * t] + 4);
  return out;
}

Status TetMesh::check() const {
  auto fail = [](const std::string& what, size_t t) {
    return Status::Error("tet mesh: " + what + " (tetrahedron " + std::to_string(t) + ")");
  };
  for (size_t t = 0; t < capacity(); ++t) {
    if (tv_[4 * t] < 0) continue;
    const int32_t* v = &tv_[4 * t];
    for (int k = 0; k < 4; ++k) {
      if (v[k] < 0 || size_t(v[k]) >= num_vertices()) return fail("invalid vertex", t);
      const int32_t w = vtet_[size_t(v[k])];
      if (w < 0 || !is_live(w) || slot_of(tet(w), v[k]) < 0)
        return fail("vertex_tet does not contain the vertex", t);
      for (int j = k + 1; j < 4; ++j)
        if (v[j] == v[k]) return fail("repeated vertex", t);
    }
    if (orient3d(point(v[0]), point(v[1]), point(v[2]), point(v[3])) >= 0)
      return fail("tetrahedron not positive", t);
    for (int k = 0; k < 4; ++k) {
      const int32_t e = tn_[4 * t + size_t(k)];
      if (e < 0) continue;
      const int32_t u = e >> 2, j = e & 3;
      if (size_t(u) >= capacity() || !is_live(u)) return fail("dead neighbor", t);
      if (tn_[size_t(e)] != int32_t(4 * t) + k) return fail("neighbor links not symmetric", t);
      if (((tc_[t] >> k) & 1) != ((tc_[size_t(u)] >> j) & 1))
        return fail("constraint flags not symmetric", t);
      if (face_key(v, k) != face_key(tet(u), j)) return fail("neighbors do not share the face", t);
    }
  }
  return Status::Ok();
}

}  // namespace vm
