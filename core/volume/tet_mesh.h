// Mutable tetrahedral mesh of one region with face adjacency: the working
// structure of volume optimization (core/volume/optimize_volume.h), where
// vertices move and local reconnections (flips, edge removal) happen in the
// style of Shewchuk ("Two discrete optimization algorithms for the
// topological improvement of tetrahedral meshes", 2002) and Klingner and
// Shewchuk ("Aggressive tetrahedral mesh improvement", IMR 2007). The region
// boundary is implicit: a face with no neighbor is a boundary face, and is
// never removed; interior faces may carry a constrained flag too.
//
// Layout: the points, fixed flags and the shared topology of
// core/volume/tet_topology.h (the kernel's records and operations, with
// kBoundary links on the region boundary). Vertex k of tet t is tet(t)[k];
// face k is the face opposite vertex k. Every live tetrahedron is positive:
// tet_volume6 > 0 (orient3d < 0 in the predicates' convention).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh/volume_mesh.h"
#include "core/util/result.h"
#include "core/volume/tet_topology.h"

namespace vm {

class Delaunay3D;

class TetMesh {
 public:
  /// Neighbor code of a boundary face (no tetrahedron of the region across).
  static constexpr int32_t kBoundary = -1;

  TetMesh() = default;

  /// The tetrahedra of `kernel` tagged `tag`. vertex_map: one entry per
  /// kernel vertex, the mesh vertex it becomes (-1: not used by the
  /// region; precondition: every vertex of a tagged tetrahedron is mapped,
  /// to ids in [0, num_vertices)). Faces to tetrahedra of another tag (or
  /// ghosts) become boundary faces; interior constrained faces stay
  /// constrained. fixed: one flag per mesh vertex (1: never moved).
  static Result<TetMesh> from_kernel(const Delaunay3D& kernel, int32_t tag,
                                     const std::vector<int32_t>& vertex_map, int32_t num_vertices,
                                     std::vector<uint8_t> fixed);

  /// From flat arrays: points (3 doubles per vertex), tets (4 indices each,
  /// positive), fixed (one flag per vertex). Faces shared by two tetrahedra
  /// become interior faces, the others boundary faces. Errors: bad sizes or
  /// indices, a face shared by more than two tetrahedra.
  static Result<TetMesh> from_arrays(std::vector<double> points, const std::vector<int32_t>& tets,
                                     std::vector<uint8_t> fixed);

  // ---- Vertices.
  size_t num_vertices() const { return pts_.size() / 3; }
  const double* point(int32_t v) const { return &pts_[3 * size_t(v)]; }
  const std::vector<double>& points() const { return pts_; }
  bool is_fixed(int32_t v) const { return fixed_[size_t(v)] != 0; }
  /// Moves vertex v to p (3 doubles) without any check: the caller has
  /// verified that every tetrahedron around v stays positive.
  void set_point(int32_t v, const double* p) {
    for (int k = 0; k < 3; ++k) pts_[3 * size_t(v) + size_t(k)] = p[k];
  }
  /// A live tetrahedron incident to v (-1 if v is used by none).
  int32_t vertex_tet(int32_t v) const { return topo_.vertex_tet[size_t(v)]; }
  /// Appends a vertex at p (3 doubles), not fixed and not yet used.
  int32_t add_vertex(const double* p);

  // ---- Tetrahedra.
  size_t capacity() const { return topo_.capacity(); }
  bool is_live(int32_t t) const { return topo_.is_live(t); }
  const int32_t* tet(int32_t t) const { return topo_.tet(t); }
  /// 4 * u + j (u across face k of t, j the face's index in u), or kBoundary.
  int32_t neighbor(int32_t t, int k) const { return topo_.neighbor(t, k); }
  /// Whether face k of t may never be removed (boundary or constrained).
  bool is_constrained(int32_t t, int k) const {
    return topo_.neighbor(t, k) < 0 || topo_.is_constrained(t, k);
  }
  size_t num_tets() const { return topo_.num_live(); }
  /// The shared topology (core/volume/tet_topology.h; tags unused).
  const TetTopology& topology() const { return topo_; }

  /// Live tetrahedra around vertex v, into out (cleared first).
  void star(int32_t v, std::vector<int32_t>& out) const { tets_around_vertex(topo_, v, out); }
  /// The tetrahedra around edge (a, b) of tetrahedron t in cyclic order and
  /// the ring vertices: ring_tets[i] is (a, b, ring[i], ring[i + 1]) up to
  /// an even permutation (positive). Returns false (outputs unspecified)
  /// when the edge lies on the boundary or a face around it is
  /// constrained, i.e. when it cannot be removed, or when more than
  /// max_size tetrahedra surround it. Precondition: a and b are vertices of
  /// live t.
  bool edge_ring(int32_t t, int32_t a, int32_t b, std::vector<int32_t>& ring_tets,
                 std::vector<int32_t>& ring, int max_size = 64) const {
    return vm::edge_ring(topo_, t, a, b, ring_tets, ring,
                         {true, max_size > 0 ? size_t(max_size) : 0});
  }

  /// Replaces the live tetrahedra old_tets (connected) by new_tets with the
  /// same boundary; new ids into new_ids. Checks only the face matching
  /// (each outer face once, inner faces twice) and that no constrained face
  /// is interior to the old set; the caller guarantees positive new
  /// tetrahedra. Returns false and changes nothing on mismatch.
  bool replace(const int32_t* old_tets, int n_old, const std::array<int32_t, 4>* new_tets,
               int n_new, std::vector<int32_t>* new_ids) {
    std::vector<int32_t>& ids = new_ids ? *new_ids : ids_;
    return replace_tets(topo_, old_tets, n_old, new_tets, n_new, ids, scratch_) ==
           ReplaceError::kNone;
  }
  /// replace() by one worker of a parallel pass: its own scratch and slot
  /// pool (see replace_tets()).
  ReplaceError replace_in(const int32_t* old_tets, int n_old,
                          const std::array<int32_t, 4>* new_tets, int n_new,
                          std::vector<int32_t>& new_ids, ReplaceScratch& scratch, SlotPool& pool) {
    return replace_tets(topo_, old_tets, n_old, new_tets, n_new, new_ids, scratch, &pool);
  }
  /// Slot pools for the workers of a parallel pass (see take_slot_pools()).
  void take_slot_pools(const std::vector<size_t>& sizes, std::vector<SlotPool>& pools) {
    vm::take_slot_pools(topo_, sizes, pools);
  }
  void return_slot_pools(std::vector<SlotPool>& pools) { vm::return_slot_pools(topo_, pools); }

  /// Positive tetrahedra (4 indices each) of the live slots in id order.
  std::vector<int32_t> tets() const;

  /// Invariants: neighbor symmetry with shared faces, positive tetrahedra
  /// (exact orient3d), vertex_tet incidences, symmetric constraint flags.
  Status check() const;

 private:
  std::vector<double> pts_;
  std::vector<uint8_t> fixed_;
  TetTopology topo_;
  ReplaceScratch scratch_;
  std::vector<int32_t> ids_;  // replace() without new_ids
};

}  // namespace vm
