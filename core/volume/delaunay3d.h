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
//   core/geom/hilbert_sort.h).
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

#include "core/geom/hilbert_sort.h"
#include "core/util/result.h"
#include "core/volume/tet_topology.h"

namespace vm {

/// Delaunay3D::build()'s options.
struct DelaunayBuildOptions {
  SpatialSortOptions sort;
  /// Past the first parts * min_part_points points, the points are
  /// inserted in rounds of `parts` slabs at once (Delaunay3D's partitioned
  /// insertion, on the threads of core/util/parallel.h), each round
  /// at most doubling the vertices; a point whose walk or cavity leaves
  /// its slab waits for the next round, with slabs across another axis,
  /// and after `retry_rounds` rounds with no new points for the
  /// sequential end. Points mostly on a surface (the first points' hull
  /// has more than a face per 16 vertices) stay sequential: slabs would cut
  /// most of their long tetrahedra, and no part owns the hull's ghosts. The
  /// slabs, and so the result (tetrahedron ids included), depend on
  /// `parts`, never on the thread count. parts = 1: all sequential.
  /// 1 <= parts <= 64, min_part_points >= 1, retry_rounds >= 0.
  int parts = 2;
  int64_t min_part_points = 8192;
  int retry_rounds = 2;
};

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
    kForeign,      ///< partitioned round: another part's tetrahedra needed
  };
  struct InsertResult {
    InsertStatus status = InsertStatus::kInvalid;
    int32_t vertex = -1;
  };

  enum class LocationType { kInside, kOnFace, kOnEdge, kOnVertex, kOutside, kForeign };
  /// `tet` contains the point in its closure (a ghost tetrahedron when
  /// kOutside); `vertex` is set for kOnVertex.
  struct Location {
    int32_t tet = -1;
    LocationType type = LocationType::kOutside;
    int32_t vertex = -1;
  };

  Delaunay3D() = default;

  using BuildOptions = DelaunayBuildOptions;
  /// Delaunay tetrahedralization of `points` (3 doubles per point, finite),
  /// inserted in BRIO/Hilbert order. Vertex i is point i. Points that
  /// coincide with an earlier-inserted one are not vertices
  /// (duplicate_of(i) names the vertex). Errors: non-finite coordinates,
  /// fewer than 4 non-coplanar points, options out of range.
  static Result<Delaunay3D> build(std::vector<double> points, const BuildOptions& options = {});

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
  const std::vector<int32_t>& last_inserted_tets() const { return seq_.new_tets; }
  /// A tetrahedron with edge (a, b), or -1.
  int32_t find_edge(int32_t a, int32_t b) const;
  /// A tetrahedron t with face (a, b, c) as face k (any orientation), or -1.
  int32_t find_face(int32_t a, int32_t b, int32_t c, int* k) const;
  /// Scratch of the queries below: one per thread (an open-addressing set
  /// of the tetrahedra listed, valid where gen matches).
  static constexpr uint32_t kAroundSlots = 1024;
  struct AroundScratch {
    uint32_t gen = 0;
    std::vector<uint32_t> stamp = std::vector<uint32_t>(kAroundSlots);
    std::vector<int32_t> key = std::vector<int32_t>(kAroundSlots);
    std::vector<int32_t> tets;
  };
  /// find_edge() and find_face() without the shared visit marks: any number
  /// may run at the same time while nothing changes the triangulation, each
  /// with its own scratch. The same results.
  int32_t find_edge(int32_t a, int32_t b, AroundScratch& s) const;
  int32_t find_face(int32_t a, int32_t b, int32_t c, int* k, AroundScratch& s) const;
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
    /// build()'s partitioned rounds (DelaunayBuildOptions).
    int64_t build_rounds = 0;
  };
  const Stats& stats() const { return seq_.stats; }

  // ---- Partitioned insertion, after Marot, Pellerin and Remacle ("One
  // machine, one minute, three billion tetrahedra", IJNME 117, 2019,
  // section 4: parallel insertion in partitions with ownership). Between
  // begin_partitions() and end_partitions() the parts insert at the same
  // time, one thread per part. A part walks, searches and replaces only
  // tetrahedra whose four vertices are in it, and reads their neighbors;
  // no other part writes those (another part's cavity and the neighbors
  // it relinks have three or four vertices in that part), so the parts
  // share no written data and what a part does depends on its own calls
  // alone, never on the others' timing. Meanwhile the calls below, the
  // const accessors of such tetrahedra, of vertices, and tag(), are all
  // that may be used.
  static constexpr uint8_t kNoPart = 255;
  struct PartBudget {
    int32_t vertices = 0;  ///< new vertices the part may insert
    int32_t tets = 0;      ///< fresh tetrahedron slots it may take
  };
  /// Starts a round: vertex v is in part vertex_part[v] (one byte per
  /// vertex: < budgets.size() <= 254, or kNoPart); part i may insert
  /// budgets[i].vertices vertices, numbered part_vertex_begin(i), + 1, ...
  /// in insertion order (they are in part i). Precondition: no round open.
  void begin_partitions(std::vector<uint8_t> vertex_part, const std::vector<PartBudget>& budgets);
  /// The id of part i's first new vertex in the round.
  int32_t part_vertex_begin(int part) const { return parts_[size_t(part)].vertex_begin; }
  /// locate() in part `part` (-1: the whole triangulation, locate()):
  /// LocationType::kForeign (tet -1) when the walk from `hint`, a
  /// tetrahedron of the part, would leave the part's tetrahedra.
  Location locate_in(int part, const double* p, int32_t hint) const;
  /// insert(p, hint, true, min_distance) in part `part` (-1: insert()):
  /// kForeign, nothing changed, when the walk from `hint` or the cavity
  /// needs a tetrahedron of another part, or the part's budget is spent.
  InsertResult insert_in(int part, const double* p, int32_t hint, double min_distance);
  /// Whether tetrahedron t is part `part`'s: its four vertices are in the
  /// part (always true for part -1).
  bool in_part(int part, int32_t t) const;
  /// tets_around_vertex() for a vertex of part `part` (-1: the same), in
  /// the same order, without the shared visit marks.
  void tets_around_vertex_in(int part, int32_t v, std::vector<int32_t>& out) const;
  /// Ends the round: the parts' new vertices are renumbered after the
  /// vertices before the round, part by part in insertion order, and their
  /// unused slots freed. Returns, per round id minus the vertex count
  /// before the round, the final id (-1 for unused ids).
  std::vector<int32_t> end_partitions();

 private:
  static constexpr int32_t kFree = TetTopology::kFree;
  /// The tetrahedra around v in tets_around_vertex()'s order, without the
  /// shared visit marks, into s.tets, until stop(t) is true for one (which
  /// is returned; else -1).
  template <class Stop>
  int32_t around_until(int32_t v, AroundScratch& s, Stop&& stop) const;

  /// The ring of edge (a, b) of t (edge_ring) for flip `name`, which needs
  /// exactly n tetrahedra around it; an error naming the flip when (a, b) is
  /// not an edge of a live t or the ring has another size.
  Status flip_ring(const char* name, int32_t t, int32_t a, int32_t b, size_t n,
                   std::vector<int32_t>& ring_tets, std::vector<int32_t>& ring) const;

  /// The state of one inserting thread: the searches' and the star's
  /// scratch, the walk's memory and random state, counters; in a
  /// partitioned round also its part, its free slots and its vertex ids
  /// (begin_partitions()).
  struct Worker;
  InsertResult insert_vertex(Worker& w, int32_t v, int32_t hint, bool respect_constraints,
                             double min_distance = 0);
  /// A finite vertex of the cavity's boundary faces closer than
  /// sqrt(d2) to p.
  bool cavity_vertex_within(const Worker& w, const double* p, double d2) const;
  /// The walk to a tetrahedron holding p; o3_bound: orient3d's static
  /// filter bound for a box holding p and every vertex (HUGE_VAL: none).
  /// In a partitioned round -1 when it would leave w's tetrahedra.
  int32_t walk(Worker& w, const double* p, int32_t hint, double o3_bound) const;
  /// Whether p is in the box of the vertices, which grow_box() extends.
  bool in_box(const double* p) const;
  void grow_box(const double* p);
  /// Whether every vertex of t is in w's part (always, out of a
  /// partitioned round).
  bool owns(const Worker& w, int32_t t) const;
  bool conflict(int32_t t, const double* p, int32_t pv, bool strict_hull) const;
  bool finite_conflict(int32_t t, const double* p, int32_t pv) const;
  bool sos_conflict(int32_t t, const double* p, int32_t pv) const;
  bool ghost_conflict(int32_t t, const double* p, int32_t pv, bool strict_hull) const;
  /// The Bowyer-Watson cavity of p from t0 into w.cavity / w.boundary;
  /// kVerify: constrained faces respected and the result checked
  /// star-shaped (false: fall back to find_cavity_checked; also false with
  /// w.foreign set when it would take a tetrahedron w does not own).
  template <bool kVerify>
  bool bowyer_watson(Worker& w, int32_t t0, const double* p, int32_t pv, bool respect_constraints);
  bool find_cavity_checked(Worker& w, int32_t t0, const double* p, int32_t pv,
                           bool respect_constraints);
  /// Whether p is strictly inside encoded face e (its tetrahedron's side).
  bool sees_face(int32_t e, const double* p) const;
  /// Shrinks the verified Bowyer-Watson cavity (stamp `in`) until every
  /// boundary face sees p; false (w.cavity left invalid) when p's
  /// tetrahedron t0 would leave it or p is on a face of t0.
  bool shrink_to_star(Worker& w, int32_t t0, const double* p, uint32_t in);
  /// Keeps the tetrahedra of w.cavity stamped `in` and collects their
  /// boundary faces (neighbor not stamped `in`) into w.boundary.
  void keep_cavity(Worker& w, uint32_t in);
  /// A fresh even visit mark for w (m + 1 is free for a second set).
  uint32_t visit_stamp(Worker& w) const;
  /// kBuild (build(), no constraints, tags or partitions): leaves
  /// vertex_tet, constraint bits and tags to build()'s final pass.
  template <bool kBuild>
  void star(Worker& w, int32_t pv);
  /// star(): the links between the new tetrahedra (w.new_tets, on
  /// w.boundary) of a cavity too large for the table, by a hash of the
  /// boundary edges.
  void link_star_by_hash(Worker& w);
  bool new_tet_valid(const std::array<int32_t, 4>& q, const std::vector<int32_t>& around) const;
  void init_first_tet(int32_t a, int32_t b, int32_t c, int32_t d);
  /// build()'s insertions of every vertex but the first tetrahedron's
  /// (first[0..3]), sequential or in partitioned rounds (BuildOptions).
  void build_insertions(const BuildOptions& o, const int32_t first[4]);
  /// One partitioned round of build_insertions(): items (vertex ids, in
  /// insertion order) in `parts` slabs across `axis`; vertices [0, nv) are
  /// the inserted ones and items. Leaves in items those not inserted
  /// (ascending).
  void build_round(int parts, int axis, int32_t nv, std::vector<int32_t>& items);
  /// build()'s sequential insertion of vertex v (its walk from the last
  /// insertion), noting a duplicate.
  void build_insert(int32_t v);
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
  bool building_ = false;  // inside build()'s insertions

  // star(): per cavity boundary face, its vertices in kFaceOut order, the
  // link to the outside, their local ids and, out of build(), its
  // constraint bit and tag; per vertex + 1, the generation (high 24 bits)
  // and local id (low 8 bits) of the last star that numbered it; the table
  // of directed boundary edges between local ids. A closed triangulated
  // sphere with V vertices has 2 V - 4 faces, so kMaxTableFaces faces have
  // at most kLocal vertices.
  struct BoundaryFace {
    int32_t v[3];
    int32_t outside;
    int32_t tag;
    uint8_t constrained;
    uint8_t local[3];
  };
  static constexpr int kLocal = 64;
  static constexpr size_t kMaxTableFaces = 2 * kLocal - 4;
  struct EdgeSlot {  // star(): open-addressing hash of boundary edges
    int32_t u, w;    // the edge, u < w
    int32_t face;    // encoded face (p, u, w) of the first new tet seen
    uint32_t gen;    // live iff == hash_gen
  };
  struct Worker {
    int part = -1;  // -1: the whole triangulation, out of a partitioned round
    int32_t last = 0;
    uint64_t rng = 0x2545f4914f6cdd1dull;
    Stats stats;
    std::vector<int32_t> cavity, boundary;  // tets; encoded faces
    // The verified search's fixed lists (kMaxCavity and 4 kMaxCavity).
    std::vector<int32_t> cavity_buffer, boundary_buffer;
    std::vector<int32_t> new_tets, pinned, ring, queue;
    std::vector<BoundaryFace> faces;
    std::vector<uint32_t> local_id;
    uint32_t local_gen = 0;
    std::vector<int32_t> edge_table = std::vector<int32_t>(kLocal * kLocal);
    std::vector<EdgeSlot> edge_hash;
    uint32_t hash_gen = 0;
    // In a partitioned round: visit marks gen + k * gen_step (distinct
    // between the parts), the slots freed by its insertions and its range
    // of fresh slots, its range of vertex ids; foreign: the last search
    // reached a tetrahedron of another part or ran out of room.
    uint32_t gen = 0, gen_step = 2;
    std::vector<int32_t> free_slots;
    int32_t slot_next = 0, slot_end = 0;
    int32_t vertex_begin = 0, vertex_next = 0, vertex_end = 0;
    bool foreign = false;
    // The last walk stopped at a ghost of another part's (build()).
    bool beyond_hull = false;
    // tets_around_vertex_in()'s scratch.
    AroundScratch around;
  };
  // The sequential worker (queries and flips use its scratch too; the class
  // is not thread-safe out of a partitioned round) and the parts' workers.
  mutable Worker seq_;
  mutable std::vector<Worker> parts_;
  // In a partitioned round: the part of each vertex (kNoPart: none).
  std::vector<uint8_t> part_;
  int64_t round_vertices_ = 0;  // num_vertices() when the round began
};

}  // namespace vm
