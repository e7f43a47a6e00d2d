// Topology of a tetrahedral mesh over flat arrays, shared by the Delaunay
// kernel (core/volume/delaunay3d.h: ghosts on the hull, every face linked)
// and the optimizer's region mesh (core/volume/tet_mesh.h: a face with no
// neighbor is a region boundary face); docs/ARCHITECTURE.md, stage 6.
//
// The face table kFaceOut is core/mesh/volume_mesh.h's. Adjacency is
// encoded per face as 4 * tet + face (Shewchuk, "Two discrete
// optimization algorithms for the topological improvement of tetrahedral
// meshes", 2002, for the edge rings and the replacement of a set of
// tetrahedra by another with the same boundary, the building block of flips
// and edge removal). The operations take their stopping rules as
// parameters, so both meshes use one implementation.
//
// Layout: per tetrahedron one 32-byte record {v[4], n[4]} (vertex k of tet
// t is v[k]; face k is the face opposite vertex k; n[k] is 4 * u + j with u
// the tetrahedron across face k and j that face's index in u, or negative
// when there is none), a byte of constrained-face bits, a region tag (the
// kernel's; the region mesh has none); slots are live or free (kFree at
// v[0]) and free slots are reused last-freed first. Per vertex: one live
// incident tetrahedron (vertex_tet).
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/mesh/volume_mesh.h"
#include "core/util/default_init_vector.h"
#include "core/util/result.h"

namespace vm {

/// The six edges of a tetrahedron as slot pairs.
inline constexpr int kTetEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

/// Slot of x in the 4 vertices v, or -1.
inline int slot_of(const int32_t* v, int32_t x) {
  for (int k = 0; k < 4; ++k)
    if (v[k] == x) return k;
  return -1;
}

/// Whether (a, b, c, d), a permutation of (0, 1, 2, 3), is even.
inline bool parity_even(int a, int b, int c, int d) {
  const int p[4] = {a, b, c, d};
  int inv = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inv += p[i] > p[j];
  return inv % 2 == 0;
}

/// The vertices of face k of v (4 vertex ids), sorted.
inline std::array<int32_t, 3> face_key(const int32_t* v, int k) {
  std::array<int32_t, 3> f;
  for (int s = 0, n = 0; s < 4; ++s)
    if (s != k) f[size_t(n++)] = v[s];
  if (f[0] > f[1]) std::swap(f[0], f[1]);
  if (f[1] > f[2]) std::swap(f[1], f[2]);
  if (f[0] > f[1]) std::swap(f[0], f[1]);
  return f;
}

struct TetTopology {
  /// v[0] of a free slot.
  static constexpr int32_t kFree = -2;
  /// One tetrahedron (32 bytes: a cavity search or a ring walk reads both).
  struct Rec {
    int32_t v[4];
    int32_t n[4];
  };

  // The per-slot arrays: resize(n) leaves new slots uninitialized (a
  // partitioned round's parts fill their fresh slots themselves; every
  // other growth passes the free slot's values).
  DefaultInitVector<Rec> tets;             // per slot
  DefaultInitVector<uint8_t> constrained;  // per slot: bit k = face k constrained
  DefaultInitVector<int32_t> tags;         // per slot: region tag (if tagged)
  bool tagged = true;                      // false: tags stay empty
  std::vector<int32_t> free_slots;         // free slot ids, reused from the back
  std::vector<int32_t> vertex_tet;         // per vertex: a live incident slot or -1
  // Visit marks (per slot) of the searches; see visit_stamp().
  mutable DefaultInitVector<uint32_t> stamp;
  mutable uint32_t gen = 0;

  size_t capacity() const { return tets.size(); }
  size_t num_live() const { return tets.size() - free_slots.size(); }
  bool is_live(int32_t t) const { return tets[size_t(t)].v[0] != kFree; }
  const int32_t* tet(int32_t t) const { return tets[size_t(t)].v; }
  int32_t neighbor(int32_t t, int k) const { return tets[size_t(t)].n[k]; }
  /// The link stored at encoded face e = 4 * t + k.
  int32_t& link(int32_t e) { return tets[size_t(e >> 2)].n[e & 3]; }
  int32_t link(int32_t e) const { return tets[size_t(e >> 2)].n[e & 3]; }
  bool is_constrained(int32_t t, int k) const { return (constrained[size_t(t)] >> k) & 1; }

  /// Reserves room for n slots.
  void reserve(size_t n);
  /// A slot to fill: the last freed one, else a new one (vertices kFree,
  /// links -1, tag 0, not constrained). Inline: the star of every
  /// insertion calls it per new tetrahedron.
  int32_t new_slot() {
    if (!free_slots.empty()) {
      const int32_t t = free_slots.back();
      free_slots.pop_back();
      return t;
    }
    return append_slot();
  }
  /// new_slot() for k slots, into out[0..k): the free ones, then fresh
  /// ones appended together.
  void new_slots(int32_t* out, size_t k) {
    size_t i = 0;
    for (; i < k && !free_slots.empty(); ++i) {
      out[i] = free_slots.back();
      free_slots.pop_back();
    }
    if (i < k) append_slots(out + i, k - i);
  }
  /// Frees live slot t (not its links: the caller relinks its neighbors).
  void free_slot(int32_t t) {
    tets[size_t(t)].v[0] = kFree;
    constrained[size_t(t)] = 0;
    free_slots.push_back(t);
  }
  /// A fresh even mark m for `stamp`; m + 1 is free for a second set.
  uint32_t visit_stamp() const {
    if (gen > 0xfffffff0u) clear_stamps();
    gen += 2;
    return gen;
  }

 private:
  int32_t append_slot();
  void append_slots(int32_t* out, size_t k);
  void clear_stamps() const;
};

/// The 2-3 flip of face k of t (with a neighbor across): the three
/// tetrahedra (x, y, r[i], r[i + 1]) around the edge joining t's apex x =
/// v[k] and the neighbor's apex y, r the face in kFaceOut order (clockwise
/// seen from x); positive when the flip is valid. Into out[0..2].
inline void flip23_tets(const TetTopology& m, int32_t t, int k, std::array<int32_t, 4>* out) {
  const int32_t* v = m.tet(t);
  const int32_t e = m.neighbor(t, k);
  const int32_t x = v[k], y = m.tet(e >> 2)[e & 3];
  const int* f = kFaceOut[k];
  const int32_t r[3] = {v[f[0]], v[f[1]], v[f[2]]};
  for (int i = 0; i < 3; ++i) out[i] = {x, y, r[i], r[(i + 1) % 3]};
}

/// Edge removal: the two tetrahedra over the triangle (x, y, z) of ring
/// vertices (in ring order) of edge (a, b) as edge_ring() lists it:
/// (x, y, z, b) and (y, x, z, a), positive when the triangle separates a
/// from b. Into out[0..1].
inline void ring_triangle_tets(int32_t a, int32_t b, int32_t x, int32_t y, int32_t z,
                               std::array<int32_t, 4>* out) {
  out[0] = {x, y, z, b};
  out[1] = {y, x, z, a};
}

/// Stopping rules of edge_ring().
struct RingRules {
  /// Stop (false) on a constrained face around the edge.
  bool stop_at_constrained = false;
  /// Stop (false) when more tetrahedra surround the edge.
  size_t max_size = SIZE_MAX;
};

/// The tetrahedra around edge (a, b) of tetrahedron t in cyclic order and
/// the ring vertices: ring_tets[i] is (a, b, ring[i], ring[i + 1]) up to an
/// even permutation. Returns false (outputs unspecified) on a face without
/// neighbor around the edge (it lies on the boundary) or when `rules` stop.
/// Precondition: a and b are vertices of live t.
bool edge_ring(const TetTopology& m, int32_t t, int32_t a, int32_t b,
               std::vector<int32_t>& ring_tets, std::vector<int32_t>& ring,
               const RingRules& rules = {});

/// Live tetrahedra incident to vertex v (breadth-first from vertex_tet),
/// into out (cleared first).
void tets_around_vertex(const TetTopology& m, int32_t v, std::vector<int32_t>& out);

/// Why replace_tets() refused (kNoRoom: its slot pool has too few slots).
enum class ReplaceError { kNone, kConstrainedInside, kUnmatchedFace, kUncoveredFace, kNoRoom };

/// The free slots of one worker of a parallel pass, so that workers never
/// share the free list: some taken from it, then the ones the worker frees
/// (reused last freed first).
struct SlotPool {
  std::vector<int32_t> free;
  size_t room() const { return free.size(); }
};

/// Gives pools[i] (pools resized to sizes) up to sizes[i] slots from the
/// free list, never new ones: the arrays do not grow (a copy of them would
/// double the memory), so a worker may have to wait until it frees some.
void take_slot_pools(TetTopology& m, const std::vector<size_t>& sizes,
                     std::vector<SlotPool>& pools);
/// Puts the pools' slots back on the free list, pool by pool, and clears
/// the pools.
void return_slot_pools(TetTopology& m, std::vector<SlotPool>& pools);

/// Scratch of replace_tets() (kept by the caller to avoid allocations).
struct ReplaceScratch {
  struct OuterFace {
    std::array<int32_t, 3> key;
    int32_t link;  // the outer neighbor's encoded face, or negative
    uint8_t constrained;
    uint8_t used;
  };
  std::vector<OuterFace> outer;
  std::vector<int32_t> match;
  std::vector<std::array<int32_t, 3>> keys;
};

/// Replaces the live tetrahedra old_tets (n_old, connected) by new_tets
/// (n_new, 4 vertex ids each; negative ids, e.g. the kernel's infinite
/// vertex, allowed) with the same boundary; the new slot ids (old slots
/// first, in order) into ids. Checks only the face matching (each boundary
/// face of the old set once, inner faces twice) and that no constrained
/// face is inside the old set; the caller checks the orientation. New
/// tetrahedra take the tag of old_tets[0] (if tagged) and the constraint bits of the
/// boundary faces they inherit. On an error nothing changes. With a pool,
/// new slots come from it and freed ones go to it; then the call writes
/// only the old and new slots, the links of their outer neighbors through
/// the shared faces, and vertex_tet of their vertices.
ReplaceError replace_tets(TetTopology& m, const int32_t* old_tets, int n_old,
                          const std::array<int32_t, 4>* new_tets, int n_new,
                          std::vector<int32_t>& ids, ReplaceScratch& scratch,
                          SlotPool* pool = nullptr);

/// Invariants of the links, vertices and flags: per live tetrahedron,
/// vertices in [0, num_vertices) or (ghost_vertex_allowed) the ghost vertex
/// -1 at most once, no repeated vertex, vertex_tet incident; per face, a
/// negative link only if boundary_allowed, else a live neighbor linking back
/// through the same three vertices, with the same constraint flag. Returns
/// the first violation.
Status check_topology(const TetTopology& m, size_t num_vertices, bool ghost_vertex_allowed,
                      bool boundary_allowed);

}  // namespace vm
