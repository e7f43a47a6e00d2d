// Incremental 3D Delaunay triangulation over flat arrays (the kernel of the
// volume stage, docs/ARCHITECTURE.md, stage 6).
//
// - Insertion: Bowyer ("Computing Dirichlet tessellations", Comput. J. 24,
//   1981) and Watson ("Computing the n-dimensional Delaunay tessellation with
//   application to Voronoi polytopes", Comput. J. 24, 1981): the cavity of
//   tetrahedra whose circumsphere contains the new point is found by a
//   breadth-first search and re-triangulated by starring its boundary from
//   the point.
// - Order: BRIO rounds along a Hilbert curve (Amenta, Choi, Rote, SoCG 2003;
//   core/volume/spatial_sort.h).
// - Location: visibility walk, remembering and stochastic (Devillers, Pion,
//   Teillaud, "Walking in a triangulation", IJFCS 13, 2002).
// - Predicates: Shewchuk's filtered exact orient3d/insphere (DCG 18, 1997);
//   cospherical ties broken by insphere_sos (symbolic perturbation of the
//   lifted coordinates by vertex index), so every point set, grids included,
//   gets one well-defined triangulation and no flat tetrahedron.
// - Convex hull: an infinite vertex (kInfinite) and ghost tetrahedra on the
//   hull faces, so the triangulation is a closed 3-manifold and insertion
//   outside the hull is the same algorithm.
// - Flips 2-3, 3-2, 4-4 and edge removal (Shewchuk, "Two discrete
//   optimization algorithms for the topological improvement of tetrahedral
//   meshes", 2002) for boundary recovery and later sliver removal.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/util/result.h"
#include "core/volume/spatial_sort.h"
#include "core/volume/tet_topology.h"

namespace vm {

class Delaunay3D {
 public:
  /// The vertex at infinity of the ghost tetrahedra.
  static constexpr int32_t kInfinite = -1;

  enum class InsertStatus {
    kInserted,     ///< the point is the new vertex `vertex`
    kDuplicate,    ///< the point coincides with vertex `vertex`; nothing changed
    kOutsideHull,  ///< constrained mode: the point is outside the convex hull
    kBlocked,      ///< constrained / non-Delaunay mode: no star-shaped cavity
                   ///< around the point (e.g. it lies on a constrained face)
    kInvalid,      ///< a coordinate is not finite
    kTooClose,     ///< a vertex of the cavity lies within the given distance
  };
  struct InsertResult {
    InsertStatus status = InsertStatus::kInvalid;
    int32_t vertex = -1;
  };

  enum class LocationType { kInside, kOnFace, kOnEdge, kOnVertex, kOutside };
  /// `tet` contains the point in its closure (a ghost tetrahedron when
  /// kOutside); `vertex` is set for kOnVertex.
  struct Location {
    int32_t tet = -1;
    LocationType type = LocationType::kOutside;
    int32_t vertex = -1;
  };

  Delaunay3D() = default;

  /// Delaunay tetrahedralization of `points` (3 doubles per point, finite),
  /// inserted in BRIO/Hilbert order. Vertex i is point i. Points that
  /// coincide with an earlier-inserted one are not vertices
  /// (duplicate_of(i) names the vertex). Errors: non-finite coordinates,
  /// fewer than 4 non-coplanar points.
  static Result<Delaunay3D> build(std::vector<double> points,
                                  const SpatialSortOptions& sort_options = {});

  /// Inserts point p (3 doubles) as a new vertex (id num_vertices() before
  /// the call), starting the walk at tetrahedron `hint` (any live id, or -1
  /// for the last one touched). With respect_constraints the cavity never
  /// crosses a constrained face, and the point must not lie outside the
  /// convex hull (kOutsideHull). When the triangulation is no longer
  /// Delaunay (after flips) or constraints are respected, the cavity is the
  /// conflict region grown only across faces seen from p, at most 512
  /// tetrahedra, and shrunk until it is star-shaped from p; the tetrahedra
  /// whose closure holds p always stay (kBlocked if they cannot, e.g. p on a
  /// constrained face). The result is then valid but not necessarily
  /// (constrained) Delaunay. On any status other than kInserted nothing is
  /// changed. With min_distance > 0 the point is refused (kTooClose,
  /// nothing changed) if a vertex of its cavity, which holds every vertex
  /// the point would be joined to, is closer than min_distance to it.
  InsertResult insert(const double* p, int32_t hint = -1, bool respect_constraints = false,
                      double min_distance = 0);

  /// Locates p (3 doubles) by walking from `hint` (-1: the last tetrahedron
  /// touched).
  Location locate(const double* p, int32_t hint = -1) const;

  // ---- Vertices.
  size_t num_vertices() const { return pts_.size() / 3; }
  const double* point(int32_t v) const { return &pts_[3 * size_t(v)]; }
  /// 3 doubles per vertex (input points first, then inserted ones).
  const std::vector<double>& points() const { return pts_; }
  /// The vertex point v coincides with, or -1 if v is itself a vertex.
  int32_t duplicate_of(int32_t v) const { return dup_[size_t(v)]; }
  /// A live tetrahedron incident to vertex v (-1 for duplicates).
  int32_t vertex_tet(int32_t v) const { return topo_.vertex_tet[size_t(v)]; }

  // ---- Tetrahedra. Ids index flat arrays of capacity tet_capacity(); a
  // slot is live or free (reused by later insertions). Vertex k of tet t is
  // tet(t)[k]; face k is the face opposite vertex k. Finite tetrahedra are
  // positive: tet_volume6 > 0 (orient3d < 0). A ghost has one vertex
  // kInfinite; its finite face is a convex hull face, and replacing
  // kInfinite by a point beyond that face gives a positive tetrahedron.
  size_t tet_capacity() const { return topo_.capacity(); }
  bool is_live(int32_t t) const { return topo_.is_live(t); }
  bool is_ghost(int32_t t) const {
    const int32_t* v = topo_.tet(t);
    return v[0] == kInfinite || v[1] == kInfinite || v[2] == kInfinite || v[3] == kInfinite;
  }
  const int32_t* tet(int32_t t) const { return topo_.tet(t); }
  /// 4 * u + j: the tetrahedron u across face k of t, and the index j of
  /// that face in u (so neighbor(u, j) == 4 * t + k).
  int32_t neighbor(int32_t t, int k) const { return topo_.neighbor(t, k); }
  size_t num_finite_tets() const;
  /// 4 vertex ids per finite tetrahedron (positive), live slots in id order.
  std::vector<int32_t> finite_tets() const;
  /// Calls f(t) for every live finite tetrahedron id.
  template <class F>
  void for_each_finite_tet(F&& f) const {
    for (int32_t t = 0; t < int32_t(tet_capacity()); ++t)
      if (is_live(t) && !is_ghost(t)) f(t);
  }

  /// Region tag per tetrahedron (0 by default); tetrahedra created by an
  /// insertion or a flip take the tag of the one they replace.
  int32_t tag(int32_t t) const { return topo_.tags[size_t(t)]; }
  void set_tag(int32_t t, int32_t tag) { topo_.tags[size_t(t)] = tag; }

  // ---- Constrained faces (flags on both sides of the face).
  bool is_constrained(int32_t t, int k) const { return topo_.is_constrained(t, k); }
  void set_constrained(int32_t t, int k, bool on);

  // ---- Topology queries.
  /// Live tetrahedra incident to vertex v (ghosts included), into `out`.
  void tets_around_vertex(int32_t v, std::vector<int32_t>& out) const {
    vm::tets_around_vertex(topo_, v, out);
  }
  /// The tetrahedra created by the last successful insertion (insert() or
  /// build()), ghosts included: exactly the tetrahedra incident to the new
  /// vertex, as tets_around_vertex would list them (in another order). Valid
  /// until the next insertion or flip.
  const std::vector<int32_t>& last_inserted_tets() const { return new_; }
  /// A tetrahedron with edge (a, b), or -1.
  int32_t find_edge(int32_t a, int32_t b) const;
  /// A tetrahedron t with face (a, b, c) as face k (any orientation), or -1.
  int32_t find_face(int32_t a, int32_t b, int32_t c, int* k) const;
  /// The n tetrahedra around edge (a, b) of tetrahedron t, in cyclic order,
  /// and the n ring vertices: ring_tets[i] is (a, b, ring_verts[i],
  /// ring_verts[(i + 1) % n]) up to an even permutation (so that tetrahedron
  /// is positive); kInfinite may appear. Precondition: t live with vertices
  /// a and b.
  void edge_ring(int32_t t, int32_t a, int32_t b, std::vector<int32_t>& ring_tets,
                 std::vector<int32_t>& ring_verts) const;

  // ---- Flips. Each checks that no constrained face is removed and that
  // every new tetrahedron is strictly positive (a new ghost: its hull face
  // is a proper triangle with no vertex of the region beyond it, so the
  // hull stays convex; this allows flips of coplanar hull faces); otherwise
  // it returns an error and changes nothing. On success the new tetrahedron
  // ids are returned and the triangulation is marked non-Delaunay
  // (is_delaunay() false).
  /// 2-3: the face k of t and its neighbor (both finite) become 3
  /// tetrahedra around the edge joining the two apexes.
  Result<std::array<int32_t, 3>> flip23(int32_t t, int k);
  /// 3-2: edge (a, b) of t, with exactly 3 tetrahedra around it, is removed.
  Result<std::array<int32_t, 2>> flip32(int32_t t, int32_t a, int32_t b);
  /// 4-4: edge (a, b) of t with 4 tetrahedra around it whose ring is planar
  /// (or any ring that admits it) is replaced by the ring diagonal starting
  /// at ring vertex c.
  Result<std::array<int32_t, 4>> flip44(int32_t t, int32_t a, int32_t b, int32_t c);
  /// Edge removal: edge (a, b) of t with n >= 3 tetrahedra around it is
  /// replaced by 2(n-2) tetrahedra over a fan triangulation of its ring;
  /// among the valid fans, the one maximizing the smallest volume
  /// (normalized by its longest edge cubed) is chosen.
  Result<std::vector<int32_t>> remove_edge(int32_t t, int32_t a, int32_t b);

  /// Replaces the live tetrahedra `old_tets` (a connected set) by `new_tets`
  /// (4 vertex ids each, kInfinite allowed once) with the same boundary. Checks: every
  /// new tetrahedron strictly positive, faces matched exactly (each boundary
  /// face of the old set once, inner faces twice), no constrained face inside
  /// the old set. Returns the new ids. The building block of the flips;
  /// public for recovery and optimization stages.
  Result<std::vector<int32_t>> replace_tets(const std::vector<int32_t>& old_tets,
                                            const std::vector<std::array<int32_t, 4>>& new_tets);

  /// The shared topology (core/volume/tet_topology.h).
  const TetTopology& topology() const { return topo_; }

  /// True until the first flip: insertions then use the fast cavity.
  bool is_delaunay() const { return delaunay_; }

  /// Checks the invariants: neighbor symmetry with matching shared faces,
  /// finite tetrahedra strictly positive, one kInfinite per ghost, vertex
  /// incidences, symmetric constraint flags; with `delaunay`, also that
  /// every finite face is locally Delaunay (insphere_sos), which implies the
  /// empty-circumsphere property. Returns the first violation.
  Status check(bool delaunay) const;

  /// Counters since construction.
  struct Stats {
    int64_t walk_steps = 0;
    int64_t cavity_tets = 0;     ///< tetrahedra removed by insertions
    int64_t boundary_faces = 0;  ///< tetrahedra created by insertions
    int64_t flips = 0;
    /// Constrained / non-Delaunay insertions whose Bowyer-Watson cavity
    /// could not be shrunk in place (too large, a ghost or a constrained
    /// face inside, or the point's tetrahedron dropped), so the checked
    /// search grew and shrank another.
    int64_t checked_cavities = 0;
    /// Constrained / non-Delaunay insertions whose Bowyer-Watson cavity
    /// was shrunk until star-shaped (no checked search needed).
    int64_t shrunk_cavities = 0;
  };
  const Stats& stats() const { return stats_; }

 private:
  static constexpr int32_t kFree = TetTopology::kFree;

  /// The ring of edge (a, b) of t (edge_ring) for flip `name`, which needs
  /// exactly n tetrahedra around it; an error naming the flip when (a, b) is
  /// not an edge of a live t or the ring has another size.
  Status flip_ring(const char* name, int32_t t, int32_t a, int32_t b, size_t n,
                   std::vector<int32_t>& ring_tets, std::vector<int32_t>& ring) const;

  InsertResult insert_vertex(int32_t v, int32_t hint, bool respect_constraints,
                             double min_distance = 0);
  /// A finite vertex of the cavity's boundary faces closer than
  /// sqrt(d2) to p.
  bool cavity_vertex_within(const double* p, double d2) const;
  /// The walk to a tetrahedron holding p; o3_bound: orient3d's static
  /// filter bound for a box holding p and every vertex (HUGE_VAL: none).
  int32_t walk(const double* p, int32_t hint, double o3_bound) const;
  /// Whether p is in the box of the vertices, which grow_box() extends.
  bool in_box(const double* p) const;
  void grow_box(const double* p);
  bool conflict(int32_t t, const double* p, int32_t pv, bool strict_hull) const;
  bool finite_conflict(int32_t t, const double* p, int32_t pv) const;
  bool sos_conflict(int32_t t, const double* p, int32_t pv) const;
  bool ghost_conflict(int32_t t, const double* p, int32_t pv, bool strict_hull) const;
  /// The Bowyer-Watson cavity of p from t0 into cavity_ / boundary_;
  /// kVerify: constrained faces respected and the result checked
  /// star-shaped (false: fall back to find_cavity_checked).
  template <bool kVerify>
  bool bowyer_watson(int32_t t0, const double* p, int32_t pv, bool respect_constraints);
  bool find_cavity_checked(int32_t t0, const double* p, int32_t pv, bool respect_constraints);
  /// Whether p is strictly inside encoded face e (its tetrahedron's side).
  bool sees_face(int32_t e, const double* p) const;
  /// Shrinks the verified Bowyer-Watson cavity (stamp `in`) until every
  /// boundary face sees p; false (cavity_ left invalid) when p's
  /// tetrahedron t0 would leave it or p is on a face of t0.
  bool shrink_to_star(int32_t t0, const double* p, uint32_t in);
  /// Keeps the tetrahedra of cavity_ stamped `in` and collects their
  /// boundary faces (neighbor not stamped `in`) into boundary_.
  void keep_cavity(uint32_t in);
  void star(int32_t pv);
  /// star(): the links between the new tetrahedra (new_, on boundary_)
  /// of a cavity too large for the table, by a hash of the boundary edges.
  void link_star_by_hash();
  bool new_tet_valid(const std::array<int32_t, 4>& q, const std::vector<int32_t>& around) const;
  void init_first_tet(int32_t a, int32_t b, int32_t c, int32_t d);
  /// The link (4 * neighbor + face) stored at encoded face e = 4 * t + k.
  int32_t& link(int32_t e) { return topo_.link(e); }
  int32_t link(int32_t e) const { return topo_.link(e); }

  std::vector<double> pts_;      // 3 per vertex
  std::vector<int32_t> sos_id_;  // while building: vertex -> input index
  std::vector<int32_t> dup_;     // per vertex: coincident vertex or -1
  // The bounding box of the vertices and the static filter bounds of the
  // predicates for points in it (core/geom/predicates.h).
  double lo_[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi_[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  double o3_bound_ = HUGE_VAL, is_bound_ = HUGE_VAL;
  // Tetrahedra (records, constraint bits, tags, free slots), vertex_tet
  // and visit marks.
  TetTopology topo_;
  ReplaceScratch replace_scratch_;
  bool delaunay_ = true;
  mutable Stats stats_;

  // Scratch (mutable: queries reuse them too; the class is not thread-safe).
  mutable int32_t last_ = 0;
  mutable uint64_t rng_ = 0x2545f4914f6cdd1dull;
  std::vector<int32_t> cavity_, boundary_;  // tets; encoded faces
  std::vector<int32_t> new_, pinned_, ring_scratch_;
  // star(): per boundary face, the local ids of its vertices in kFaceOut
  // order; per vertex + 1, the generation (high 24 bits) and local id (low
  // 8 bits) of the last star that numbered it; the table of directed
  // boundary edges between local ids. A closed triangulated sphere with V
  // vertices has 2 V - 4 faces, so kMaxTableFaces faces have at most kLocal
  // vertices.
  struct FaceSide {
    uint8_t local[3];
  };
  std::vector<FaceSide> sides_;
  static constexpr int kLocal = 64;
  static constexpr size_t kMaxTableFaces = 2 * kLocal - 4;
  std::vector<uint32_t> local_id_;
  uint32_t local_gen_ = 0;
  std::vector<int32_t> edge_table_ = std::vector<int32_t>(kLocal * kLocal);
  struct EdgeSlot {  // star(): open-addressing hash of boundary edges
    int32_t u, w;    // the edge, u < w
    int32_t face;    // encoded face (p, u, w) of the first new tet seen
    uint32_t gen;    // live iff == hash_gen_
  };
  std::vector<EdgeSlot> edge_hash_;
  uint32_t hash_gen_ = 0;
  mutable std::vector<int32_t> queue_;
};

}  // namespace vm
