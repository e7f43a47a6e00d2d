// Shared topology operations of the tetrahedral meshes (Shewchuk 2002 for
// edge rings and replacements); see tet_topology.h for the layout.
#include "core/volume/tet_topology.h"

#include <algorithm>
#include <string>

namespace vm {

void TetTopology::reserve(size_t n) {
  tets.reserve(n);
  constrained.reserve(n);
  if (tagged) tags.reserve(n);
  stamp.reserve(n);
}

int32_t TetTopology::append_slot() {
  int32_t t;
  append_slots(&t, 1);
  return t;
}

void TetTopology::append_slots(int32_t* out, size_t k) {
  const size_t n = tets.size();
  tets.resize(n + k, {{kFree, kFree, kFree, kFree}, {-1, -1, -1, -1}});
  constrained.resize(n + k, 0);
  if (tagged) tags.resize(n + k, 0);
  stamp.resize(n + k, 0);
  for (size_t i = 0; i < k; ++i) out[i] = int32_t(n + i);
}

void TetTopology::clear_stamps() const {
  std::fill(stamp.begin(), stamp.end(), 0);
  gen = 0;
}

bool edge_ring(const TetTopology& m, int32_t t, int32_t a, int32_t b,
               std::vector<int32_t>& ring_tets, std::vector<int32_t>& ring,
               const RingRules& rules) {
  ring_tets.clear();
  ring.clear();
  const int32_t* v = m.tet(t);
  const int sa = slot_of(v, a), sb = slot_of(v, b);
  int sc = -1, sd = -1;
  for (int s = 0; s < 4; ++s)
    if (s != sa && s != sb) (sc < 0 ? sc : sd) = s;
  if (!parity_even(sa, sb, sc, sd)) std::swap(sc, sd);
  int32_t c = v[sc], d = v[sd];
  int32_t cur = t;
  int k = sc;  // slot of c in cur
  for (size_t n = 0; n < rules.max_size; ++n) {
    ring_tets.push_back(cur);
    ring.push_back(c);
    // Next: across the face (a, b, d), opposite c.
    const TetTopology::Rec& r = m.tets[size_t(cur)];
    const int32_t e = r.n[k];
    if (e < 0 || (rules.stop_at_constrained && ((m.constrained[size_t(cur)] >> k) & 1)))
      return false;
    cur = e >> 2;
    if (cur == t) return true;
    // In cur, the face (a, b, d) is opposite slot e & 3: that vertex is the
    // next d, and d becomes the vertex to cross.
    const int32_t* w = m.tet(cur);
    k = 0;
    while (w[k] != d) ++k;
    c = d;
    d = w[e & 3];
  }
  return false;  // more than max_size tetrahedra around the edge
}

void tets_around_vertex(const TetTopology& m, int32_t v, std::vector<int32_t>& out) {
  out.clear();
  const int32_t t0 = m.vertex_tet[size_t(v)];
  if (t0 < 0) return;
  const uint32_t mark = m.visit_stamp();
  uint32_t* stamp = m.stamp.data();
  out.push_back(t0);
  stamp[size_t(t0)] = mark;
  for (size_t i = 0; i < out.size(); ++i) {
    const TetTopology::Rec& r = m.tets[size_t(out[i])];
    // The neighbors' records and marks fetched together (memory bound).
    for (int j = 0; j < 4; ++j)
      if (r.n[j] >= 0) {
        __builtin_prefetch(&m.tets[size_t(r.n[j] >> 2)]);
        __builtin_prefetch(&stamp[size_t(r.n[j] >> 2)]);
      }
    const int sv = slot_of(r.v, v);
    for (int j = 0; j < 4; ++j) {
      if (j == sv || r.n[j] < 0) continue;
      const int32_t n = r.n[j] >> 2;
      if (stamp[size_t(n)] == mark) continue;
      stamp[size_t(n)] = mark;
      out.push_back(n);
    }
  }
}

namespace {

// Equality of face keys without memcmp (the hot loop of replace_tets()).
inline bool same_key(const std::array<int32_t, 3>& a, const std::array<int32_t, 3>& b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

}  // namespace

void take_slot_pools(TetTopology& m, const std::vector<size_t>& sizes,
                     std::vector<SlotPool>& pools) {
  pools.assign(sizes.size(), SlotPool{});
  for (size_t i = 0; i < sizes.size(); ++i)
    for (size_t k = 0; k < sizes[i] && !m.free_slots.empty(); ++k) {
      pools[i].free.push_back(m.free_slots.back());
      m.free_slots.pop_back();
    }
}

void return_slot_pools(TetTopology& m, std::vector<SlotPool>& pools) {
  for (SlotPool& p : pools) m.free_slots.insert(m.free_slots.end(), p.free.begin(), p.free.end());
  pools.clear();
}

ReplaceError replace_tets(TetTopology& m, const int32_t* old_tets, int n_old,
                          const std::array<int32_t, 4>* new_tets, int n_new,
                          std::vector<int32_t>& ids, ReplaceScratch& scratch, SlotPool* pool) {
  if (pool && n_new > n_old && pool->room() < size_t(n_new - n_old)) return ReplaceError::kNoRoom;
  auto in_old = [&](int32_t u) {
    for (int i = 0; i < n_old; ++i)
      if (old_tets[i] == u) return true;
    return false;
  };
  // Phase 1: the boundary faces of the old set.
  auto& outer = scratch.outer;
  outer.clear();
  for (int i = 0; i < n_old; ++i) {
    const int32_t t = old_tets[i];
    for (int k = 0; k < 4; ++k) {
      const int32_t e = m.neighbor(t, k);
      if (e >= 0 && in_old(e >> 2)) {
        if (m.is_constrained(t, k)) return ReplaceError::kConstrainedInside;
        continue;
      }
      outer.push_back({face_key(m.tet(t), k), e, uint8_t(m.is_constrained(t, k)), 0});
    }
  }
  // Phase 2: match the faces of the new set (keys computed once): each to
  // an unused boundary face, else to a face of a later new tetrahedron.
  auto& match = scratch.match;  // outer index, or -2 - (4 i + k)
  auto& keys = scratch.keys;
  match.assign(4 * size_t(n_new), -1);
  keys.resize(4 * size_t(n_new));
  for (int i = 0; i < n_new; ++i)
    for (int k = 0; k < 4; ++k) keys[4 * size_t(i) + size_t(k)] = face_key(new_tets[i].data(), k);
  for (int f = 0; f < 4 * n_new; ++f) {
    if (match[size_t(f)] != -1) continue;
    const auto& key = keys[size_t(f)];
    int32_t found = -1;
    for (size_t o = 0; o < outer.size() && found < 0; ++o)
      if (!outer[o].used && same_key(outer[o].key, key)) found = int32_t(o);
    if (found >= 0) {
      outer[size_t(found)].used = 1;
      match[size_t(f)] = found;
      continue;
    }
    for (int g = 4 * (f / 4 + 1); g < 4 * n_new && found < 0; ++g)
      if (match[size_t(g)] == -1 && same_key(keys[size_t(g)], key)) {
        found = g;
        match[size_t(g)] = -2 - f;
        match[size_t(f)] = -2 - g;
      }
    if (found < 0) return ReplaceError::kUnmatchedFace;
  }
  for (const auto& f : outer)
    if (!f.used) return ReplaceError::kUncoveredFace;
  // Phase 3: commit: old slots reused first, then new ones, then the
  // remaining old slots freed.
  const int32_t tag = m.tagged ? m.tags[size_t(old_tets[0])] : 0;
  for (int i = 0; i < n_old; ++i)
    for (int32_t x : m.tets[size_t(old_tets[i])].v)
      if (x >= 0) m.vertex_tet[size_t(x)] = -1;
  ids.resize(size_t(n_new));
  auto new_slot = [&]() {
    if (!pool) return m.new_slot();
    const int32_t t = pool->free.back();
    pool->free.pop_back();
    return t;
  };
  for (int i = 0; i < n_new; ++i) ids[size_t(i)] = i < n_old ? old_tets[i] : new_slot();
  for (int i = n_new; i < n_old; ++i) {
    if (!pool) {
      m.free_slot(old_tets[i]);
      continue;
    }
    m.tets[size_t(old_tets[i])].v[0] = TetTopology::kFree;
    m.constrained[size_t(old_tets[i])] = 0;
    pool->free.push_back(old_tets[i]);
  }
  for (int i = 0; i < n_new; ++i) {
    const int32_t t = ids[size_t(i)];
    std::copy(new_tets[i].begin(), new_tets[i].end(), m.tets[size_t(t)].v);
    if (m.tagged) m.tags[size_t(t)] = tag;
    m.constrained[size_t(t)] = 0;
    for (int32_t x : new_tets[i])
      if (x >= 0) m.vertex_tet[size_t(x)] = t;
  }
  for (int i = 0; i < n_new; ++i)
    for (int k = 0; k < 4; ++k) {
      const int32_t mi = match[4 * size_t(i) + size_t(k)];
      const int32_t e = 4 * ids[size_t(i)] + k;
      if (mi >= 0) {
        const auto& f = outer[size_t(mi)];
        m.link(e) = f.link;
        if (f.link >= 0) m.link(f.link) = e;
        m.constrained[size_t(ids[size_t(i)])] |= uint8_t(f.constrained << k);
      } else {
        const int32_t other = -2 - mi;
        m.link(e) = 4 * ids[size_t(other / 4)] + other % 4;
      }
    }
  return ReplaceError::kNone;
}

Status check_topology(const TetTopology& m, size_t num_vertices, bool ghost_vertex_allowed,
                      bool boundary_allowed) {
  auto fail = [](const std::string& what, size_t t) {
    return Status::Error(what + " (tetrahedron " + std::to_string(t) + ")");
  };
  for (size_t t = 0; t < m.capacity(); ++t) {
    if (!m.is_live(int32_t(t))) continue;
    const int32_t* v = m.tet(int32_t(t));
    int ghosts = 0;
    for (int k = 0; k < 4; ++k) {
      if (v[k] == -1 && ghost_vertex_allowed) {
        ++ghosts;
        continue;
      }
      if (v[k] < 0 || size_t(v[k]) >= num_vertices) return fail("invalid vertex id", t);
      const int32_t w = m.vertex_tet[size_t(v[k])];
      if (w < 0 || size_t(w) >= m.capacity() || !m.is_live(w) || slot_of(m.tet(w), v[k]) < 0)
        return fail("vertex_tet of a vertex does not contain it", t);
      for (int j = k + 1; j < 4; ++j)
        if (v[j] == v[k]) return fail("repeated vertex", t);
    }
    if (ghosts > 1) return fail("more than one infinite vertex", t);
    for (int k = 0; k < 4; ++k) {
      const int32_t e = m.neighbor(int32_t(t), k);
      if (e < 0) {
        if (boundary_allowed) continue;
        return fail("dead neighbor", t);
      }
      const int32_t u = e >> 2, j = e & 3;
      if (size_t(u) >= m.capacity() || !m.is_live(u)) return fail("dead neighbor", t);
      if (m.link(e) != int32_t(4 * t) + k) return fail("neighbor links not symmetric", t);
      if (m.is_constrained(u, j) != m.is_constrained(int32_t(t), k))
        return fail("constraint flags not symmetric", t);
      if (face_key(v, k) != face_key(m.tet(u), j))
        return fail("neighbors do not share the face", t);
    }
  }
  return Status::Ok();
}

}  // namespace vm
