// Bowyer-Watson 3D Delaunay (Bowyer 1981, Watson 1981) with BRIO/Hilbert
// order (Amenta, Choi, Rote 2003), remembering stochastic visibility walk
// (Devillers, Pion, Teillaud 2002), exact predicates with symbolic
// perturbation (Shewchuk 1997; Edelsbrunner, Muecke 1990) and flips
// (Shewchuk 2002). See delaunay3d.h for the data layout.
//
// Insertion phases: (1) walk to a tetrahedron containing the point, (2)
// cavity search: breadth-first over conflicting tetrahedra; in constrained /
// non-Delaunay mode the same search not crossing constrained faces, bounded
// and verified star-shaped (every boundary face strictly visible from the
// point), else shrunk in place until it is (tetrahedra behind a boundary
// face leave it), else, when that would drop the point's own tetrahedron,
// too large, or holding a ghost or a constrained face, the "checked"
// search, which crosses only faces seen from the point, stops at
// constrained faces and shrinks the cavity until every boundary face is
// strictly visible; (3) star: one new tetrahedron per
// cavity boundary face, linked to the outside through the old face and to
// each other through a table indexed by local ids of the boundary's
// vertices (a hash of the boundary edges for very large cavities).
// build(): past its first points, rounds of slabs inserting at the same
// time, each only in its own tetrahedra (the partitioned insertion of
// Marot, Pellerin, Remacle, "One machine, one minute, three billion
// tetrahedra", IJNME 117, 2019, section 4), unless the points lie mostly
// on a surface.
// Predicates: a static filter bound from the vertices' box, then the
// semi-static one, then the exact predicate (core/geom/predicates.h).
#include "core/volume/delaunay3d.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/geom/predicates.h"
#include "core/util/parallel.h"
#include "core/volume/slabs.h"

namespace vm {
namespace {

// Bound on the cavity of the non-Delaunay / constrained insertion (so that
// an insertion stays local).
constexpr size_t kMaxCavity = 512;

inline int inf_slot(const int32_t* v) {
  for (int k = 0; k < 4; ++k)
    if (v[k] == Delaunay3D::kInfinite) return k;
  return -1;
}

// kOther[f][j]: the two slots other than f and j (f != j).
constexpr int kOther[4][4][2] = {{{-1, -1}, {2, 3}, {1, 3}, {1, 2}},
                                 {{2, 3}, {-1, -1}, {0, 3}, {0, 2}},
                                 {{1, 3}, {0, 3}, {-1, -1}, {0, 1}},
                                 {{1, 2}, {0, 2}, {0, 1}, {-1, -1}}};

bool collinear(const double* a, const double* b, const double* c) {
  double a2[2] = {a[2], a[0]}, b2[2] = {b[2], b[0]}, c2[2] = {c[2], c[0]};
  return orient2d(a, b, c) == 0 && orient2d(a + 1, b + 1, c + 1) == 0 && orient2d(a2, b2, c2) == 0;
}

bool same_point(const double* a, const double* b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

}  // namespace

// ---------------------------------------------------------------- building

Result<Delaunay3D> Delaunay3D::build(std::vector<double> points, const BuildOptions& options) {
  if (!(options.parts >= 1 && options.parts <= 64) || !(options.min_part_points >= 1) ||
      !(options.retry_rounds >= 0))
    return Result<Delaunay3D>::Error(
        "Delaunay build: parts = " + std::to_string(options.parts) +
        ", min_part_points = " + std::to_string(options.min_part_points) +
        ", retry_rounds = " + std::to_string(options.retry_rounds) +
        "; options need 1 <= parts <= 64, min_part_points >= 1, retry_rounds >= 0");
  if (points.size() % 3 != 0) return Result<Delaunay3D>::Error("points: size not a multiple of 3");
  for (double x : points)
    if (!std::isfinite(x)) return Result<Delaunay3D>::Error("points: non-finite coordinate");
  const int64_t n = int64_t(points.size() / 3);
  if (n > int64_t(INT32_MAX / 8))
    return Result<Delaunay3D>::Error("points: too many for 32-bit tetrahedron ids");
  Delaunay3D d;
  // Vertices are numbered in insertion order while building, so that
  // consecutive insertions touch nearby memory (the input order is
  // arbitrary); Phase 3 restores the input numbering. Ties are broken by
  // input index throughout (sos_id_), so the result does not depend on it.
  std::vector<int32_t> order = brio_hilbert_order(points, options.sort);
  d.pts_.resize(points.size());
  for (int64_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k)
      d.pts_[3 * size_t(i) + k] = points[3 * size_t(order[size_t(i)]) + k];
  d.sos_id_ = order;
  d.dup_.assign(size_t(n), -1);
  for (int64_t i = 0; i < n; ++i) d.grow_box(d.point(int32_t(i)));
  d.topo_.vertex_tet.assign(size_t(n), -1);

  // Phase 1: the first tetrahedron from the first 4 affinely independent
  // points of the order.
  int32_t ib = -1, ic = -1, id = -1;
  for (int32_t i = 1; i < n && ib < 0; ++i)
    if (!same_point(d.point(0), d.point(i))) ib = i;
  for (int32_t i = ib + 1; ib > 0 && i < n && ic < 0; ++i)
    if (!collinear(d.point(0), d.point(ib), d.point(i))) ic = i;
  for (int32_t i = ic + 1; ic > 0 && i < n && id < 0; ++i)
    if (orient3d(d.point(0), d.point(ib), d.point(ic), d.point(i)) != 0) id = i;
  if (id < 0)
    return Result<Delaunay3D>::Error(
        "points: fewer than 4 affinely independent points (all coplanar, collinear or equal)");
  // About 6.7 tetrahedra a vertex (build_insertions() adds the room its
  // rounds leave unused).
  d.topo_.reserve(size_t(n) * 7 + 16);
  d.init_first_tet(0, ib, ic, id);

  // Phase 2: the other points in order.
  d.building_ = true;
  const int32_t first[4] = {0, ib, ic, id};
  d.build_insertions(options, first);
  d.building_ = false;

  // Phase 3: back to input numbering, and vertex_tet, which the stars
  // above left to this pass.
  std::vector<int32_t> vtet(static_cast<size_t>(n), -1), dup(static_cast<size_t>(n));
  for (int32_t t = 0; t < int32_t(d.topo_.capacity()); ++t) {
    int32_t* v = d.topo_.tets[size_t(t)].v;
    if (v[0] == kFree) continue;
    for (int k = 0; k < 4; ++k)
      if (v[k] >= 0) vtet[size_t(v[k] = order[size_t(v[k])])] = t;
  }
  for (int64_t i = 0; i < n; ++i) {
    const int32_t o = d.dup_[size_t(i)];
    dup[size_t(order[size_t(i)])] = o >= 0 ? order[size_t(o)] : -1;
  }
  d.topo_.vertex_tet.swap(vtet);
  d.dup_.swap(dup);
  d.pts_.swap(points);
  d.sos_id_.clear();
  return d;
}

void Delaunay3D::build_insertions(const BuildOptions& o, const int32_t first[4]) {
  const int32_t n = int32_t(num_vertices());
  auto is_first = [&](int32_t v) { return v == first[1] || v == first[2] || v == first[3]; };
  // Phase 2a: sequential, each walk starting where the previous insertion
  // ended, up to parts * min_part_points vertices (all of them with one
  // part or few points).
  const int64_t start = int64_t(o.parts) * o.min_part_points;
  int32_t v = 1;
  auto insert_up_to = [&](int32_t end) {
    for (; v < end; ++v)
      if (!is_first(v)) build_insert(v);
  };
  insert_up_to(o.parts < 2 || int64_t(n) < 2 * start ? n : int32_t(start));
  // Points mostly on a surface (the hull has more than one face per 16
  // vertices so far) stay sequential: a slab cuts their long tetrahedra,
  // and points on the hull need ghosts, which no part owns.
  if (v < n) {
    int64_t hull_faces = 0;
    for (int32_t t = 0; t < int32_t(tet_capacity()); ++t) hull_faces += is_live(t) && is_ghost(t);
    if (16 * hull_faces > int64_t(v)) return insert_up_to(n);
    // Room for the fresh slots the rounds leave unused (7 per point tried,
    // the points left over from a round tried again, 4096 per part), so
    // that no round moves the arrays.
    int rounds = o.retry_rounds + 1;
    for (int64_t m = v; m < n; m *= 2) ++rounds;
    topo_.reserve(size_t(n) * 8 + size_t(rounds) * size_t(o.parts) * 4096 + 16);
  }
  // Phase 2b: rounds of slabs, each adding at most as many points as there
  // are vertices, with the ones left over from the round before; slabs
  // across x, y, z in turn. Rounds with no new points retry those left.
  std::vector<int32_t> items, left;
  int retries = 0;
  for (int round = 0; v < n || (!left.empty() && retries < o.retry_rounds); ++round) {
    if (v == n) ++retries;
    // The new points first (in order, each walk short), then those left.
    const int32_t end = int32_t(std::min<int64_t>(n, 2 * int64_t(v)));
    items.clear();
    for (; v < end; ++v)
      if (!is_first(v)) items.push_back(v);
    items.insert(items.end(), left.begin(), left.end());
    build_round(o.parts, round % 3, v, items);
    left.swap(items);
    ++seq_.stats.build_rounds;
    if (left.size() < size_t(o.min_part_points) && v == n) break;
  }
  // Phase 2c: what is left, sequentially.
  for (int32_t u : left) build_insert(u);
}

void Delaunay3D::build_insert(int32_t v) {
  const InsertResult r = insert_vertex(seq_, v, -1, false);
  if (r.status == InsertStatus::kDuplicate) dup_[size_t(v)] = r.vertex;
}

void Delaunay3D::build_round(int parts, int axis, int32_t nv, std::vector<int32_t>& items) {
  if (items.empty()) return;
  // Slabs of equal point count across `axis`; a vertex is in the slab its
  // coordinate falls in.
  std::vector<double> xs(items.size());
  for (size_t i = 0; i < items.size(); ++i) xs[i] = point(items[i])[axis];
  const Slabs slabs = equal_count_slabs(xs, axis, size_t(parts));
  std::vector<uint8_t> vertex_part(static_cast<size_t>(nv));
  parallel_for(size_t(nv), size_t(1) << 16, [&](size_t begin, size_t end) {
    for (size_t u = begin; u < end; ++u) vertex_part[u] = uint8_t(slabs.of(point(int32_t(u))));
  });
  std::vector<std::vector<int32_t>> lists(static_cast<size_t>(parts)), left(lists.size()),
      outside(lists.size());
  for (int32_t u : items) lists[vertex_part[size_t(u)]].push_back(u);
  // Fresh slots: a new vertex takes about 6.7 more tetrahedra than it frees.
  std::vector<PartBudget> budgets(lists.size());
  for (int j = 0; j < parts; ++j)
    budgets[size_t(j)].tets = int32_t(7 * lists[size_t(j)].size() + 4096);
  begin_partitions(std::move(vertex_part), budgets);
  // Each slab's first tetrahedron: the sequential walk to its first points,
  // until one lands in a tetrahedron of the slab (none: the slab waits;
  // points outside the hull, or near another slab, do not).
  std::vector<int32_t> start(lists.size(), -1);
  for (int j = 0; j < parts; ++j)
    for (size_t i = 0; i < std::min<size_t>(lists[size_t(j)].size(), 64) && start[size_t(j)] < 0;
         ++i) {
      const int32_t t = walk(seq_, point(lists[size_t(j)][i]), -1, o3_bound_);
      if (owns(parts_[size_t(j)], t)) start[size_t(j)] = t;
      seq_.last = t;
    }
  parallel_for(size_t(parts), 1, [&](size_t begin, size_t end) {
    for (size_t j = begin; j < end; ++j) {
      Worker& w = parts_[j];
      int32_t hint = start[j];
      for (int32_t u : lists[j]) {
        if (hint < 0 || w.gen > 0xf0000000u) {
          left[j].push_back(u);
          continue;
        }
        w.beyond_hull = false;
        const InsertResult r = insert_vertex(w, u, hint, false);
        if (r.status == InsertStatus::kInserted)
          hint = w.last;
        else if (r.status == InsertStatus::kDuplicate)
          dup_[size_t(u)] = r.vertex;
        else
          (w.beyond_hull ? outside : left)[j].push_back(u);
      }
    }
  });
  for (int j = parts - 1; j >= 0; --j)
    if (parts_[size_t(j)].last >= 0) seq_.last = parts_[size_t(j)].last;
  end_partitions();
  // Points outside the hull now (no part owns a ghost), so that the next
  // rounds see the whole hull.
  items.clear();
  for (const std::vector<int32_t>& l : outside) items.insert(items.end(), l.begin(), l.end());
  std::sort(items.begin(), items.end());
  for (int32_t u : items) build_insert(u);
  items.clear();
  for (const std::vector<int32_t>& l : left) items.insert(items.end(), l.begin(), l.end());
  std::sort(items.begin(), items.end());
}

void Delaunay3D::init_first_tet(int32_t a, int32_t b, int32_t c, int32_t d) {
  if (orient3d(point(a), point(b), point(c), point(d)) > 0) std::swap(a, b);
  const int32_t base[4] = {a, b, c, d};
  int32_t ids[5];
  for (int32_t& t : ids) t = topo_.new_slot();
  std::copy(base, base + 4, topo_.tets[size_t(ids[0])].v);
  for (int k = 0; k < 4; ++k) {
    int32_t* g = topo_.tets[size_t(ids[k + 1])].v;
    std::copy(base, base + 4, g);
    g[k] = kInfinite;
    // Replacing a vertex by a point on the other side of its face flips
    // the orientation: swap two finite slots to restore it.
    int i = (k + 1) % 4, j = (k + 2) % 4;
    std::swap(g[i], g[j]);
  }
  // Link every pair of faces with the same vertex set.
  for (int x = 0; x < 5; ++x)
    for (int kx = 0; kx < 4; ++kx) {
      const int32_t* vx = topo_.tets[size_t(ids[x])].v;
      for (int y = x + 1; y < 5; ++y)
        for (int ky = 0; ky < 4; ++ky) {
          const int32_t* vy = topo_.tets[size_t(ids[y])].v;
          int shared = 0;
          for (int s = 0; s < 4; ++s)
            if (s != kx && slot_of(vy, vx[s]) >= 0 && slot_of(vy, vx[s]) != ky) ++shared;
          if (shared == 3) {
            topo_.tets[size_t(ids[x])].n[kx] = 4 * ids[y] + ky;
            topo_.tets[size_t(ids[y])].n[ky] = 4 * ids[x] + kx;
          }
        }
    }
  for (int32_t v : base) topo_.vertex_tet[size_t(v)] = ids[0];
  seq_.last = ids[0];
}

bool Delaunay3D::in_box(const double* p) const {
  return p[0] >= lo_[0] && p[0] <= hi_[0] && p[1] >= lo_[1] && p[1] <= hi_[1] && p[2] >= lo_[2] &&
         p[2] <= hi_[2];
}

void Delaunay3D::grow_box(const double* p) {
  double extent = 0;
  for (int k = 0; k < 3; ++k) {
    lo_[k] = std::min(lo_[k], p[k]);
    hi_[k] = std::max(hi_[k], p[k]);
    extent = std::max(extent, hi_[k] - lo_[k]);
  }
  o3_bound_ = orient3d_static_bound(extent);
  is_bound_ = insphere_static_bound(extent);
}

inline bool Delaunay3D::owns(const Worker& w, int32_t t) const {
  if (w.part < 0) return true;
  const int32_t* v = tet(t);
  if ((v[0] | v[1] | v[2] | v[3]) < 0) return false;  // a ghost
  const uint8_t* part = part_.data();
  const uint8_t me = uint8_t(w.part);
  return part[v[0]] == me && part[v[1]] == me && part[v[2]] == me && part[v[3]] == me;
}

inline uint32_t Delaunay3D::visit_stamp(Worker& w) const {
  if (w.part < 0) return topo_.visit_stamp();
  w.gen += w.gen_step;
  return w.gen;
}

// ---------------------------------------------------------------- location

int32_t Delaunay3D::walk(Worker& w, const double* p, int32_t hint, double o3_bound) const {
  const bool parted = w.part >= 0;
  if (parted && (hint < 0 || !owns(w, hint))) return -1;
  int32_t t = hint >= 0 && size_t(hint) < tet_capacity() && is_live(hint) ? hint : w.last;
  if (!is_live(t)) {
    t = 0;
    while (!is_live(t)) ++t;
  }
  if (is_ghost(t)) t = neighbor(t, inf_slot(tet(t))) >> 2;
  int32_t prev = -1;
  const int64_t max_steps = int64_t(tet_capacity()) * 4 + 64;
  for (int64_t step = 0; step < max_steps; ++step) {
    if (is_ghost(t)) return t;  // entered across a hull face p is beyond
    const int32_t* v = tet(t);
    w.rng ^= w.rng << 13;
    w.rng ^= w.rng >> 7;
    w.rng ^= w.rng << 17;
    const int start = int(w.rng & 3);
    int32_t next = -1;
    for (int j = 0; j < 4; ++j) {
      const int k = (start + j) & 3;
      const int32_t n = neighbor(t, k) >> 2;
      if (n == prev) continue;  // p is strictly inside that face
      const int* f = kFaceOut[k];
      if (orient3d_fast(point(v[f[0]]), point(v[f[1]]), point(v[f[2]]), p, o3_bound) < 0) {
        next = n;
        break;
      }
    }
    if (next < 0) return t;
    if (parted && !owns(w, next)) {
      w.beyond_hull = is_ghost(next);  // p beyond a hull face: outside the hull
      return -1;
    }
    prev = t;
    t = next;
    ++w.stats.walk_steps;
  }
  // Not expected (the stochastic walk terminates with probability 1): scan.
  if (parted) return -1;
  for (int32_t s = 0; s < int32_t(tet_capacity()); ++s) {
    if (!is_live(s) || is_ghost(s)) continue;
    const int32_t* v = tet(s);
    bool inside = true;
    for (int k = 0; k < 4 && inside; ++k) {
      const int* f = kFaceOut[k];
      inside = orient3d(point(v[f[0]]), point(v[f[1]]), point(v[f[2]]), p) >= 0;
    }
    if (inside) return s;
  }
  for (int32_t s = 0; s < int32_t(tet_capacity()); ++s) {
    if (!is_live(s) || !is_ghost(s)) continue;
    const int32_t* v = tet(s);
    const int g = inf_slot(v);
    const double* q[4];
    for (int k = 0; k < 4; ++k) q[k] = k == g ? p : point(v[k]);
    if (orient3d(q[0], q[1], q[2], q[3]) < 0) return s;
  }
  return t;
}

Delaunay3D::Location Delaunay3D::locate(const double* p, int32_t hint) const {
  return locate_in(-1, p, hint);
}

Delaunay3D::Location Delaunay3D::locate_in(int part, const double* p, int32_t hint) const {
  Location loc;
  if (topo_.tets.empty()) return loc;
  Worker& w = part < 0 ? seq_ : parts_[size_t(part)];
  loc.tet = walk(w, p, hint, in_box(p) ? o3_bound_ : HUGE_VAL);
  if (loc.tet < 0) {
    loc.type = LocationType::kForeign;
    return loc;
  }
  if (is_ghost(loc.tet)) return loc;
  const int32_t* v = tet(loc.tet);
  int zeros = 0;
  for (int k = 0; k < 4; ++k) {
    if (same_point(point(v[k]), p)) {
      loc.type = LocationType::kOnVertex;
      loc.vertex = v[k];
      return loc;
    }
    const int* f = kFaceOut[k];
    zeros += orient3d(point(v[f[0]]), point(v[f[1]]), point(v[f[2]]), p) == 0;
  }
  loc.type = zeros == 0   ? LocationType::kInside
             : zeros == 1 ? LocationType::kOnFace
                          : LocationType::kOnEdge;
  return loc;
}

// ---------------------------------------------------------------- insertion

[[gnu::always_inline]] inline bool Delaunay3D::finite_conflict(int32_t t, const double* p,
                                                               int32_t pv) const {
  const int32_t* v = tet(t);
  // Positive tetrahedra have orient3d < 0, so "inside" is insphere < 0.
  const double s = insphere_fast(point(v[0]), point(v[1]), point(v[2]), point(v[3]), p, is_bound_);
  if (s != 0) return s < 0;
  return sos_conflict(t, p, pv);
}

bool Delaunay3D::sos_conflict(int32_t t, const double* p, int32_t pv) const {
  const int32_t* v = tet(t);
  const double* a = point(v[0]);
  const double* b = point(v[1]);
  const double* c = point(v[2]);
  const double* d = point(v[3]);
  if (sos_id_.empty()) return insphere_sos(a, b, c, d, p, v[0], v[1], v[2], v[3], pv) < 0;
  const int32_t* id = sos_id_.data();
  return insphere_sos(a, b, c, d, p, id[v[0]], id[v[1]], id[v[2]], id[v[3]], id[pv]) < 0;
}

[[gnu::always_inline]] inline bool Delaunay3D::conflict(int32_t t, const double* p, int32_t pv,
                                                        bool strict_hull) const {
  const int32_t* v = tet(t);
  // Live tetrahedra have no kFree vertex: negative only for kInfinite.
  if ((v[0] | v[1] | v[2] | v[3]) >= 0) return finite_conflict(t, p, pv);
  return ghost_conflict(t, p, pv, strict_hull);
}

bool Delaunay3D::ghost_conflict(int32_t t, const double* p, int32_t pv, bool strict_hull) const {
  const int32_t* v = tet(t);
  const int g = inf_slot(v);
  const double* q[4];
  for (int k = 0; k < 4; ++k) q[k] = k == g ? p : point(v[k]);
  double o = orient3d_fast(q[0], q[1], q[2], q[3], o3_bound_);
  if (o != 0) return o < 0;  // p strictly beyond the hull face
  if (strict_hull) return false;
  // p in the plane of the hull face: inside the ghost's "sphere" iff inside
  // the circumcircle of the face, which every sphere through the face
  // shares; the finite neighbor decides (with the same perturbation).
  return finite_conflict(neighbor(t, g) >> 2, p, pv);
}

// Out of line: inlined into insert_vertex, its vectors' push_back calls
// were not.
template <bool kVerify>
[[gnu::noinline]] bool Delaunay3D::bowyer_watson(Worker& w, int32_t t0, const double* p, int32_t pv,
                                                 bool respect_constraints) {
  // Bowyer-Watson's search from t0 (which holds p). Unverified (the
  // triangulation is Delaunay, nothing constrained): the conflict region,
  // always star-shaped (in a partitioned round, false with w.foreign set
  // when it takes a tetrahedron w does not own). Verified: not crossing
  // constrained faces, and any doubt (a ghost, a constrained face inside,
  // too many tetrahedra) returns false, and the caller falls back to
  // find_cavity_checked; a boundary face not strictly visible from p has the
  // cavity shrunk in place (shrink_to_star) first. When the conflict region
  // is locally Delaunay it is star-shaped from p (p in ball(t) but not in
  // ball(n) across a locally Delaunay face puts p strictly on t's side, up
  // to ties), so this usually succeeds; when it does, the cavity is exactly
  // what find_cavity_checked would find (every tetrahedron of a star-shaped
  // region is reached from p across faces seen from inside) without the
  // shrinking passes.
  if (kVerify && is_ghost(t0)) return false;
  const uint32_t in = visit_stamp(w), out = in + 1;
  const bool parted = w.part >= 0;
  // Local copies of the arrays' bases: the searches below write through
  // int32 pointers, so the compiler would reload them from the vectors.
  const TetTopology::Rec* const tets = topo_.tets.data();
  uint32_t* const stamp = topo_.stamp.data();
  const uint8_t* const constrained = topo_.constrained.data();
  // The lists: the worker's vectors; verified, fixed buffers (the cavity
  // is bounded by kMaxCavity tetrahedra, its faces by 4 kMaxCavity), with
  // no capacity test per push, copied into the vectors at the end.
  int32_t* cav = nullptr;
  int32_t* bnd = nullptr;
  size_t n_cav = 0, n_bnd = 0;
  if constexpr (kVerify) {
    if (w.cavity_buffer.size() < kMaxCavity) w.cavity_buffer.resize(kMaxCavity);
    if (w.boundary_buffer.size() < 4 * kMaxCavity) w.boundary_buffer.resize(4 * kMaxCavity);
    cav = w.cavity_buffer.data();
    bnd = w.boundary_buffer.data();
  } else {
    w.cavity.clear();
    w.boundary.clear();
  }
  auto push_cavity = [&](int32_t t) {
    if constexpr (kVerify)
      cav[n_cav++] = t;
    else
      w.cavity.push_back(t);
  };
  auto push_boundary = [&](int32_t e) {
    if constexpr (kVerify)
      bnd[n_bnd++] = e;
    else
      w.boundary.push_back(e);
  };
  auto cavity_size = [&] {
    if constexpr (kVerify)
      return n_cav;
    else
      return w.cavity.size();
  };
  auto cavity_at = [&](size_t i) {
    if constexpr (kVerify)
      return cav[i];
    else
      return w.cavity[i];
  };
  // A tetrahedron's four neighbors' records and marks are fetched when it
  // joins the cavity, some iterations before they are read (refinement, in
  // a large mesh and an order that jumps, waits for memory; a build in
  // BRIO order less).
  auto fetch_around = [&](int32_t t) {
    const int32_t* links = tets[size_t(t)].n;
    for (int k = 0; k < 4; ++k) {
      const int32_t n = links[k] >> 2;
      __builtin_prefetch(&tets[size_t(n)]);
      __builtin_prefetch(&stamp[size_t(n)]);
    }
  };
  push_cavity(t0);
  stamp[size_t(t0)] = in;
  fetch_around(t0);
  for (size_t i = 0; i < cavity_size(); ++i) {
    const int32_t t = cavity_at(i);
    const int32_t* links = tets[size_t(t)].n;
    const unsigned cons = kVerify && respect_constraints ? constrained[size_t(t)] : 0u;
    for (int k = 0; k < 4; ++k) {
      const int32_t e = 4 * t + k;
      const int32_t n = links[k] >> 2;
      const uint32_t s = stamp[size_t(n)];
      if (kVerify && ((cons >> k) & 1u)) {
        if (s == in) return false;  // a constrained face inside the cavity
        push_boundary(e);           // n may still be reached another way
        continue;
      }
      if (s == in) continue;
      if (s != out && conflict(n, p, pv, false)) {
        if (!kVerify && parted && !owns(w, n)) return !(w.foreign = true);
        if (kVerify) {
          const int32_t* v = tets[size_t(n)].v;
          if ((v[0] | v[1] | v[2] | v[3]) < 0 || cavity_size() >= kMaxCavity) return false;
          if (parted && !owns(w, n)) return !(w.foreign = true);
        }
        stamp[size_t(n)] = in;
        push_cavity(n);
        fetch_around(n);
      } else {
        stamp[size_t(n)] = out;
        push_boundary(e);
      }
    }
  }
  if constexpr (!kVerify) {
    return true;
  } else {
    w.cavity.assign(cav, cav + n_cav);
    w.boundary.assign(bnd, bnd + n_bnd);
    // Star-shaped: p strictly inside every boundary face (its new
    // tetrahedron positive); else shrunk until it is.
    for (size_t i = 0; i < n_bnd; ++i)
      if (!sees_face(bnd[i], p)) return shrink_to_star(w, t0, p, in);
    return true;
  }
}

bool Delaunay3D::sees_face(int32_t e, const double* p) const {
  const int32_t* v = tet(e >> 2);
  const int* f = kFaceOut[e & 3];
  return orient3d_fast(point(v[f[0]]), point(v[f[1]]), point(v[f[2]]), p, o3_bound_) > 0;
}

bool Delaunay3D::shrink_to_star(Worker& w, int32_t t0, const double* p, uint32_t in) {
  // The tetrahedron holding p stays; when p lies on one of its faces the
  // checked search decides (it keeps every tetrahedron whose closure holds p).
  for (int k = 0; k < 4; ++k)
    if (!sees_face(4 * t0 + k, p)) return false;
  // A tetrahedron with a boundary face p does not see strictly leaves the
  // cavity; its faces to the tetrahedra still in become boundary faces and
  // are checked in turn. No constrained face is inside (the search did not
  // cross any), and a region whose boundary faces all see p holds p's
  // tetrahedron and is star-shaped from p.
  const uint32_t out = in + 1;
  std::vector<int32_t>& todo = w.queue;
  todo.assign(w.boundary.begin(), w.boundary.end());
  while (!todo.empty()) {
    const int32_t e = todo.back();
    todo.pop_back();
    const int32_t t = e >> 2;
    if (topo_.stamp[size_t(t)] != in || sees_face(e, p)) continue;
    if (t == t0) return false;
    topo_.stamp[size_t(t)] = out;
    for (int k = 0; k < 4; ++k) {
      const int32_t across = link(4 * t + k);
      if (topo_.stamp[size_t(across >> 2)] == in) todo.push_back(across);
    }
  }
  keep_cavity(w, in);
  ++w.stats.shrunk_cavities;
  return true;
}

void Delaunay3D::keep_cavity(Worker& w, uint32_t in) {
  size_t m = 0;
  for (int32_t t : w.cavity)
    if (topo_.stamp[size_t(t)] == in) w.cavity[m++] = t;
  w.cavity.resize(m);
  w.boundary.clear();
  for (int32_t t : w.cavity)
    for (int k = 0; k < 4; ++k)
      if (topo_.stamp[size_t(link(4 * t + k) >> 2)] != in) w.boundary.push_back(4 * t + k);
}

bool Delaunay3D::find_cavity_checked(Worker& w, int32_t t0, const double* p, int32_t pv,
                                     bool respect_constraints) {
  // Phase 2a: the tetrahedra whose closure holds p (one; two if p is on a
  // face; the ring if on an edge) are pinned: they are in conflict, and the
  // faces through p are inside their union, so they never need to leave
  // the cavity, unless a constrained face through p separates them.
  w.pinned.clear();
  w.pinned.push_back(t0);
  if (!is_ghost(t0)) {
    const int32_t* v = tet(t0);
    int zero[4], nz = 0;
    for (int k = 0; k < 4; ++k) {
      const int* f = kFaceOut[k];
      if (orient3d_fast(point(v[f[0]]), point(v[f[1]]), point(v[f[2]]), p, o3_bound_) == 0)
        zero[nz++] = k;
    }
    if (nz == 1) {
      w.pinned.push_back(neighbor(t0, zero[0]) >> 2);
    } else if (nz == 2) {
      int32_t e[2], m = 0;
      for (int s = 0; s < 4; ++s)
        if (s != zero[0] && s != zero[1]) e[m++] = v[s];
      edge_ring(t0, e[0], e[1], w.pinned, w.ring);
    }
  }
  for (int32_t t : w.pinned)
    if (!owns(w, t)) return !(w.foreign = true);
  const uint32_t in = visit_stamp(w), out = in + 1;
  w.cavity.clear();
  for (int32_t t : w.pinned) {
    w.cavity.push_back(t);
    topo_.stamp[size_t(t)] = in;
  }
  if (respect_constraints)
    for (int32_t t : w.pinned)
      for (int k = 0; k < 4; ++k)
        if (is_constrained(t, k) && topo_.stamp[size_t(neighbor(t, k) >> 2)] == in)
          return false;  // p on a constrained face
  // Phase 2b: conflict search, not crossing constrained faces, only
  // outward (across faces that p sees from inside: the triangulation need
  // not be Delaunay, and flat tetrahedra have huge circumspheres), and
  // bounded in size so that an insertion stays local.
  auto positive_with_p = [&](int32_t t, int k) {
    int32_t q[4];
    std::copy(tet(t), tet(t) + 4, q);
    q[k] = -2;  // p
    const int g = inf_slot(q);
    if (g >= 0) {  // a new ghost on a horizon edge: its hull face must not be flat
      const double* e[2];
      for (int s = 0, m = 0; s < 4; ++s)
        if (s != g && s != k) e[m++] = point(q[s]);
      return !collinear(e[0], e[1], p);
    }
    const double* c[4];
    for (int s = 0; s < 4; ++s) c[s] = q[s] == -2 ? p : point(q[s]);
    return orient3d(c[0], c[1], c[2], c[3]) < 0;
  };
  for (size_t i = 0; i < w.cavity.size() && w.cavity.size() < kMaxCavity; ++i) {
    const int32_t t = w.cavity[i];
    for (int k = 0; k < 4; ++k) {
      const int32_t n = neighbor(t, k) >> 2;
      const uint32_t s = topo_.stamp[size_t(n)];
      if (s == in || s == out) continue;
      if (respect_constraints && is_constrained(t, k)) continue;
      if (!positive_with_p(t, k)) continue;
      if (conflict(n, p, pv, false)) {
        if (!owns(w, n)) return !(w.foreign = true);
        topo_.stamp[size_t(n)] = in;
        w.cavity.push_back(n);
      } else {
        topo_.stamp[size_t(n)] = out;
      }
    }
  }
  // Phase 2c: shrink until star-shaped: every boundary face strictly
  // visible from p (its new tetrahedron positive) and no constrained face
  // inside the cavity.
  bool changed = true;
  while (changed) {
    changed = false;
    for (size_t i = 0; i < w.cavity.size(); ++i) {
      const int32_t t = w.cavity[i];
      if (topo_.stamp[size_t(t)] != in) continue;
      for (int k = 0; k < 4; ++k) {
        const int32_t n = neighbor(t, k) >> 2;
        int32_t drop = -1;
        if (topo_.stamp[size_t(n)] == in) {
          if (!(respect_constraints && is_constrained(t, k))) continue;
          // A constrained face inside: keep the side p is on.
          drop = positive_with_p(t, k) ? n : t;
        } else if (!positive_with_p(t, k)) {
          drop = t;
        }
        if (drop < 0) continue;
        if (std::find(w.pinned.begin(), w.pinned.end(), drop) != w.pinned.end()) return false;
        topo_.stamp[size_t(drop)] = out;
        changed = true;
        if (drop == t) break;
      }
    }
  }
  keep_cavity(w, in);
  return true;
}

template <bool kBuild>
void Delaunay3D::star(Worker& w, int32_t pv) {
  // Phase 3a: the new tetrahedron on face f of cavity tetrahedron t, whose
  // vertices in kFaceOut order are (a, b, c), is (p, a, b, c): positive (p
  // is on the side of t's vertex f, and (f, kFaceOut[f]) is an even
  // permutation), with face 0 the old face, linked to the outside. Faces
  // 1, 2, 3 hold p and the boundary edges b->c, c->a and a->b. The faces
  // are read first, so that the new tetrahedra can take the cavity's
  // slots, still in cache (as in Marot, Pellerin, Remacle, "One machine,
  // one minute, three billion tetrahedra", IJNME 117, 2019, section 3).
  const size_t nb = w.boundary.size(), nc = w.cavity.size();
  const TetTopology::Rec* const tets_in = topo_.tets.data();
  const uint8_t* const constrained_in = topo_.constrained.data();
  const int32_t* const tags_in = topo_.tags.data();
  w.faces.resize(nb);
  for (size_t i = 0; i < nb; ++i) {
    const int32_t t = w.boundary[i] >> 2;
    const int f = w.boundary[i] & 3;
    const TetTopology::Rec& o = tets_in[size_t(t)];
    const int* fo = kFaceOut[f];
    BoundaryFace& b = w.faces[i];
    b.v[0] = o.v[fo[0]], b.v[1] = o.v[fo[1]], b.v[2] = o.v[fo[2]];
    b.outside = o.n[f];
    if constexpr (!kBuild) {
      b.constrained = uint8_t((constrained_in[size_t(t)] >> f) & 1u);
      b.tag = tags_in[size_t(t)];
    }
  }
  // Phase 3b: slots: the cavity's, then free or appended ones (the part's
  // own in a partitioned round, room checked by insert_in()); cavity slots
  // left over are freed.
  w.new_tets.resize(nb);
  std::copy(w.cavity.begin(), w.cavity.begin() + std::min(nb, nc), w.new_tets.begin());
  if (w.part < 0 && nb > nc) topo_.new_slots(w.new_tets.data() + nc, nb - nc);
  for (size_t i = nc; i < nb && w.part >= 0; ++i) {
    if (!w.free_slots.empty()) {
      w.new_tets[i] = w.free_slots.back();
      w.free_slots.pop_back();
    } else {  // a fresh slot (begin_partitions()): its record is written below
      const int32_t t = w.new_tets[i] = w.slot_next++;
      topo_.stamp[size_t(t)] = 0;
      topo_.constrained[size_t(t)] = 0;
      if (topo_.tagged) topo_.tags[size_t(t)] = 0;
    }
  }
  for (size_t i = nb; i < nc; ++i) {
    const int32_t t = w.cavity[i];
    if (w.part < 0) {
      topo_.free_slot(t);
    } else {
      topo_.tets[size_t(t)].v[0] = kFree;
      topo_.constrained[size_t(t)] = 0;
      w.free_slots.push_back(t);
    }
  }
  // Phase 3c: the records, and the links between the new tetrahedra. The
  // cavity boundary is a closed surface, oriented by kFaceOut, so every
  // boundary edge is in exactly two boundary faces, with opposite
  // directions, whose new tetrahedra share that face. Small cavities link
  // through a table indexed by local ids of the boundary vertices (ibid.,
  // section 3.3): every new tetrahedron writes its three faces under their
  // directed edges, then reads its neighbors under the reversed edges, with
  // no search and no branch on the data. Larger ones use a hash of the
  // boundary edges.
  const bool by_table = nb <= kMaxTableFaces;
  uint32_t gen = 0;
  if (by_table) {
    if (w.local_id.size() < num_vertices() + 1) w.local_id.resize(num_vertices() + 1, 0);
    if (++w.local_gen >= (1u << 24)) {
      std::fill(w.local_id.begin(), w.local_id.end(), 0u);
      w.local_gen = 1;
    }
    gen = w.local_gen << 8;
  }
  // Indexed by vertex + 1: kInfinite is one like the others.
  uint32_t* lid = by_table ? w.local_id.data() + 1 : nullptr;
  uint32_t next = 0;
  int32_t* table = w.edge_table.data();
  // Local copies of the arrays' bases (the slots are all allocated above).
  TetTopology::Rec* const tets = topo_.tets.data();
  uint8_t* const constrained = topo_.constrained.data();
  int32_t* const tags = topo_.tags.data();
  int32_t* const vertex_tet = topo_.vertex_tet.data();
  for (size_t i = 0; i < nb; ++i) {
    const BoundaryFace& b = w.faces[i];
    const int32_t n = w.new_tets[i];
    TetTopology::Rec& r = tets[size_t(n)];
    r.v[0] = pv, r.v[1] = b.v[0], r.v[2] = b.v[1], r.v[3] = b.v[2];
    r.n[0] = b.outside;
    tets[size_t(b.outside >> 2)].n[b.outside & 3] = 4 * n;
    if constexpr (!kBuild) {
      constrained[size_t(n)] = b.constrained;
      tags[size_t(n)] = b.tag;
      for (int32_t u : b.v)
        if (u >= 0) vertex_tet[size_t(u)] = n;
    }
    if (!by_table) continue;
    uint32_t id[3];
    for (int jj = 0; jj < 3; ++jj) {
      const uint32_t x = lid[b.v[jj]];
      const bool fresh = (x & ~0xffu) != gen;
      id[jj] = fresh ? next : (x & 0xffu);
      next += fresh;
      lid[b.v[jj]] = gen | id[jj];
    }
    w.faces[i].local[0] = uint8_t(id[0]), w.faces[i].local[1] = uint8_t(id[1]);
    w.faces[i].local[2] = uint8_t(id[2]);
    table[id[0] * kLocal + id[1]] = 4 * n + 3;
    table[id[1] * kLocal + id[2]] = 4 * n + 1;
    table[id[2] * kLocal + id[0]] = 4 * n + 2;
  }
  if (by_table) {
    for (size_t i = 0; i < nb; ++i) {
      const uint8_t* side = w.faces[i].local;
      TetTopology::Rec& r = tets[size_t(w.new_tets[i])];
      r.n[1] = table[side[2] * kLocal + side[1]];
      r.n[2] = table[side[0] * kLocal + side[2]];
      r.n[3] = table[side[1] * kLocal + side[0]];
    }
  } else {
    link_star_by_hash(w);
  }
  if (!kBuild) topo_.vertex_tet[size_t(pv)] = w.new_tets[0];
  w.stats.cavity_tets += int64_t(nc);
  w.stats.boundary_faces += int64_t(nb);
  w.last = w.new_tets[0];
}

void Delaunay3D::link_star_by_hash(Worker& w) {
  const size_t nb = w.new_tets.size();
  int bits = 4;
  while ((size_t(1) << bits) < 3 * nb) ++bits;
  const size_t hsize = size_t(1) << bits;
  if (w.edge_hash.size() < hsize) w.edge_hash.resize(hsize);
  if (++w.hash_gen == 0) {
    for (EdgeSlot& s : w.edge_hash) s.gen = 0;
    w.hash_gen = 1;
  }
  const uint32_t hgen = w.hash_gen;
  const uint32_t mask = uint32_t(hsize - 1);
  EdgeSlot* table = w.edge_hash.data();
  for (size_t i = 0; i < nb; ++i) {
    const int32_t n = w.new_tets[i];
    TetTopology::Rec& r = topo_.tets[size_t(n)];
    for (int j = 1; j < 4; ++j) {  // p is vertex 0
      int32_t u = r.v[kOther[0][j][0]], x = r.v[kOther[0][j][1]];
      if (u > x) std::swap(u, x);
      uint32_t h = ((uint32_t(u) * 0x9e3779b1u) ^ (uint32_t(x) * 0x85ebca6bu)) >> (32 - bits);
      for (;; h = (h + 1) & mask) {
        EdgeSlot& s = table[h];
        if (s.gen != hgen) {
          s = {u, x, 4 * n + j, hgen};
          break;
        }
        if (s.u == u && s.w == x) {
          r.n[j] = s.face;
          link(s.face) = 4 * n + j;
          break;
        }
      }
    }
  }
}

bool Delaunay3D::cavity_vertex_within(const Worker& w, const double* p, double d2) const {
  for (int32_t e : w.boundary) {
    const int32_t* v = tet(e >> 2);
    const int* f = kFaceOut[e & 3];
    for (int j = 0; j < 3; ++j) {
      const int32_t w = v[f[j]];
      if (w < 0) continue;
      const double* q = point(w);
      const double x = q[0] - p[0], y = q[1] - p[1], z = q[2] - p[2];
      if (x * x + y * y + z * z < d2) return true;
    }
  }
  return false;
}

Delaunay3D::InsertResult Delaunay3D::insert_vertex(Worker& w, int32_t v, int32_t hint,
                                                   bool respect_constraints, double min_distance) {
  const double* p = point(v);
  const int32_t t = walk(w, p, hint, o3_bound_);
  if (t < 0) return {InsertStatus::kForeign, -1};
  if (!is_ghost(t)) {
    const int32_t* w = tet(t);
    for (int k = 0; k < 4; ++k)
      if (same_point(point(w[k]), p)) return {InsertStatus::kDuplicate, w[k]};
  } else if (respect_constraints) {
    return {InsertStatus::kOutsideHull, -1};
  }
  w.foreign = false;
  if (delaunay_ && !respect_constraints) {
    if (!bowyer_watson<false>(w, t, p, v, false)) return {InsertStatus::kForeign, -1};
  } else if (!bowyer_watson<true>(w, t, p, v, respect_constraints)) {
    if (w.foreign) return {InsertStatus::kForeign, -1};
    ++w.stats.checked_cavities;
    if (!find_cavity_checked(w, t, p, v, respect_constraints))
      return {w.foreign ? InsertStatus::kForeign : InsertStatus::kBlocked, -1};
  }
  if (min_distance > 0 && cavity_vertex_within(w, p, min_distance * min_distance))
    return {InsertStatus::kTooClose, -1};
  if (w.part >= 0 &&
      w.boundary.size() > w.cavity.size() + w.free_slots.size() + size_t(w.slot_end - w.slot_next))
    return {InsertStatus::kForeign, -1};  // no room left
  if (building_)
    star<true>(w, v);
  else
    star<false>(w, v);
  return {InsertStatus::kInserted, v};
}

Delaunay3D::InsertResult Delaunay3D::insert(const double* p, int32_t hint, bool respect_constraints,
                                            double min_distance) {
  if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]) || topo_.tets.empty())
    return {InsertStatus::kInvalid, -1};
  const int32_t v = int32_t(num_vertices());
  if (!in_box(p)) grow_box(p);
  pts_.insert(pts_.end(), {p[0], p[1], p[2]});
  dup_.push_back(-1);
  topo_.vertex_tet.push_back(-1);
  InsertResult r = insert_vertex(seq_, v, hint, respect_constraints, min_distance);
  if (r.status != InsertStatus::kInserted) {
    pts_.resize(pts_.size() - 3);
    dup_.pop_back();
    topo_.vertex_tet.pop_back();
  }
  return r;
}

// ---------------------------------------------------------------- partitions

void Delaunay3D::begin_partitions(std::vector<uint8_t> vertex_part,
                                  const std::vector<PartBudget>& budgets) {
  const size_t n0 = num_vertices();
  size_t nv = 0, nt = 0;
  for (const PartBudget& b : budgets) nv += size_t(b.vertices), nt += size_t(b.tets);
  round_vertices_ = int64_t(n0);
  part_ = std::move(vertex_part);
  part_.resize(n0 + nv, kNoPart);
  pts_.resize(3 * (n0 + nv));
  dup_.resize(n0 + nv, -1);
  topo_.vertex_tet.resize(n0 + nv, -1);
  // Fresh slots for the parts, left uninitialized: a part fills those it
  // takes (its star), on its own thread, and end_partitions() frees the
  // others, so no slot is read unwritten.
  const size_t cap0 = topo_.capacity();
  topo_.tets.resize(cap0 + nt);
  topo_.constrained.resize(cap0 + nt);
  if (topo_.tagged) topo_.tags.resize(cap0 + nt);
  topo_.stamp.resize(cap0 + nt);
  // Visit marks: part i uses gen + 2 i + k * 2 parts (k >= 1), above every
  // mark used so far and distinct between the parts.
  if (topo_.gen > 0x7fffffffu) {
    std::fill(topo_.stamp.begin(), topo_.stamp.end(), 0u);
    topo_.gen = 0;
  }
  parts_.resize(budgets.size());
  int32_t vnext = int32_t(n0), tnext = int32_t(cap0);
  for (size_t i = 0; i < budgets.size(); ++i) {
    Worker& w = parts_[i];
    w.part = int(i);
    w.last = -1;
    w.rng = 0x2545f4914f6cdd1dull ^ (0x9e3779b97f4a7c15ull * (i + 1));
    w.stats = Stats{};
    w.gen = topo_.gen + 2 * uint32_t(i);
    w.gen_step = 2 * uint32_t(budgets.size());
    w.free_slots.clear();
    w.slot_next = tnext;
    w.slot_end = tnext += budgets[i].tets;
    w.vertex_begin = w.vertex_next = vnext;
    w.vertex_end = vnext += budgets[i].vertices;
    std::fill(part_.begin() + w.vertex_begin, part_.begin() + w.vertex_end, uint8_t(i));
  }
}

Delaunay3D::InsertResult Delaunay3D::insert_in(int part, const double* p, int32_t hint,
                                               double min_distance) {
  if (part < 0) return insert(p, hint, true, min_distance);
  if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    return {InsertStatus::kInvalid, -1};
  if (!in_box(p)) return {InsertStatus::kOutsideHull, -1};  // the hull is inside the box
  Worker& w = parts_[size_t(part)];
  if (w.vertex_next >= w.vertex_end || w.gen > 0xf0000000u) return {InsertStatus::kForeign, -1};
  const int32_t v = w.vertex_next;
  std::copy(p, p + 3, &pts_[3 * size_t(v)]);
  const InsertResult r = insert_vertex(w, v, hint, true, min_distance);
  if (r.status == InsertStatus::kInserted) ++w.vertex_next;
  return r;
}

bool Delaunay3D::in_part(int part, int32_t t) const {
  return part < 0 || owns(parts_[size_t(part)], t);
}

template <class Stop>
int32_t Delaunay3D::around_until(int32_t v, AroundScratch& s, Stop&& stop) const {
  // The breadth-first search of tets_around_vertex(), deduplicated by the
  // scratch's own set; a list longer than half the set is scanned instead.
  if (++s.gen == 0) {
    std::fill(s.stamp.begin(), s.stamp.end(), 0u);
    s.gen = 1;
  }
  const uint32_t gen = s.gen;
  std::vector<int32_t>& out = s.tets;
  auto first_visit = [&](int32_t t) {
    if (out.size() >= kAroundSlots / 2) return std::find(out.begin(), out.end(), t) == out.end();
    for (uint32_t h = (uint32_t(t) * 0x9e3779b1u) >> 22;; h = (h + 1) & (kAroundSlots - 1)) {
      if (s.stamp[h] != gen) {
        s.stamp[h] = gen;
        s.key[h] = t;
        return true;
      }
      if (s.key[h] == t) return false;
    }
  };
  out.clear();
  const int32_t t0 = topo_.vertex_tet[size_t(v)];
  if (t0 < 0) return -1;
  first_visit(t0);
  out.push_back(t0);
  for (size_t i = 0; i < out.size(); ++i) {
    const TetTopology::Rec& r = topo_.tets[size_t(out[i])];
    // The neighbors across the faces through v (the others' links may be
    // relinked by another part's star meanwhile, so they are never read)
    // are fetched while this one is tested (memory bound, as
    // tets_around_vertex()).
    const int sv = slot_of(r.v, v);
    for (int j = 0; j < 4; ++j)
      if (j != sv && r.n[j] >= 0) __builtin_prefetch(&topo_.tets[size_t(r.n[j] >> 2)]);
    if (stop(out[i])) return out[i];
    for (int j = 0; j < 4; ++j) {
      if (j == sv || r.n[j] < 0) continue;
      const int32_t n = r.n[j] >> 2;
      if (first_visit(n)) out.push_back(n);
    }
  }
  return -1;
}

void Delaunay3D::tets_around_vertex_in(int part, int32_t v, std::vector<int32_t>& out) const {
  if (part < 0) return tets_around_vertex(v, out);
  AroundScratch& s = parts_[size_t(part)].around;
  around_until(v, s, [](int32_t) { return false; });
  out.swap(s.tets);
}

int32_t Delaunay3D::find_edge(int32_t a, int32_t b, AroundScratch& s) const {
  if (a < 0 || size_t(a) >= num_vertices()) return -1;
  return around_until(a, s, [&](int32_t t) { return slot_of(tet(t), b) >= 0; });
}

int32_t Delaunay3D::find_face(int32_t a, int32_t b, int32_t c, int* k, AroundScratch& s) const {
  if (a < 0 || size_t(a) >= num_vertices()) return -1;
  const int32_t t = around_until(a, s, [&](int32_t u) {
    const int32_t* v = tet(u);
    return slot_of(v, b) >= 0 && slot_of(v, c) >= 0;
  });
  if (t >= 0 && k) {
    const int32_t* v = tet(t);
    for (int j = 0; j < 4; ++j)
      if (v[j] != a && v[j] != b && v[j] != c) *k = j;
  }
  return t;
}

std::vector<int32_t> Delaunay3D::end_partitions() {
  // The fresh slots no part took, never written: free slots.
  for (const Worker& w : parts_)
    for (int32_t t = w.slot_next; t < w.slot_end; ++t) {
      topo_.tets[size_t(t)] = {{kFree, kFree, kFree, kFree}, {-1, -1, -1, -1}};
      topo_.constrained[size_t(t)] = 0;
      if (topo_.tagged) topo_.tags[size_t(t)] = 0;
      topo_.stamp[size_t(t)] = 0;
    }
  const int32_t n0 = int32_t(round_vertices_);
  std::vector<int32_t> remap(num_vertices() - size_t(n0), -1);
  int32_t next = n0;
  for (const Worker& w : parts_)
    for (int32_t v = w.vertex_begin; v < w.vertex_next; ++v) remap[size_t(v - n0)] = next++;
  // Vertices move down (remap[k] <= n0 + k), in ascending order.
  for (size_t k = 0; k < remap.size(); ++k) {
    const int32_t d = remap[k];
    if (d < 0) continue;
    const size_t src = size_t(n0) + k;
    std::copy(&pts_[3 * src], &pts_[3 * src] + 3, &pts_[3 * size_t(d)]);
    topo_.vertex_tet[size_t(d)] = topo_.vertex_tet[src];
  }
  pts_.resize(3 * size_t(next));
  dup_.resize(size_t(next));
  topo_.vertex_tet.resize(size_t(next));
  if (!remap.empty())  // (a build's rounds add no vertices)
    for (TetTopology::Rec& r : topo_.tets) {
      if (r.v[0] == kFree) continue;
      for (int32_t& v : r.v)
        if (v >= n0) v = remap[size_t(v - n0)];
    }
  for (Worker& w : parts_) {
    topo_.free_slots.insert(topo_.free_slots.end(), w.free_slots.begin(), w.free_slots.end());
    for (int32_t t = w.slot_end - 1; t >= w.slot_next; --t) topo_.free_slots.push_back(t);
    topo_.gen = std::max(topo_.gen, w.gen);
    Stats& s = seq_.stats;
    s.walk_steps += w.stats.walk_steps;
    s.cavity_tets += w.stats.cavity_tets;
    s.boundary_faces += w.stats.boundary_faces;
    s.checked_cavities += w.stats.checked_cavities;
    s.shrunk_cavities += w.stats.shrunk_cavities;
    w.free_slots.clear();
  }
  part_.clear();
  round_vertices_ = 0;
  return remap;
}

// ---------------------------------------------------------------- queries

size_t Delaunay3D::num_finite_tets() const {
  size_t n = 0;
  for_each_finite_tet([&](int32_t) { ++n; });
  return n;
}

std::vector<int32_t> Delaunay3D::finite_tets() const {
  std::vector<int32_t> out;
  out.reserve(4 * num_finite_tets());
  for_each_finite_tet([&](int32_t t) { out.insert(out.end(), tet(t), tet(t) + 4); });
  return out;
}

void Delaunay3D::set_constrained(int32_t t, int k, bool on) {
  const int32_t e = neighbor(t, k);
  const int32_t u = e >> 2, j = e & 3;
  if (on) {
    topo_.constrained[size_t(t)] |= uint8_t(1u << k);
    topo_.constrained[size_t(u)] |= uint8_t(1u << j);
  } else {
    topo_.constrained[size_t(t)] &= uint8_t(~(1u << k));
    topo_.constrained[size_t(u)] &= uint8_t(~(1u << j));
  }
}

int32_t Delaunay3D::find_edge(int32_t a, int32_t b) const { return find_edge(a, b, seq_.around); }

int32_t Delaunay3D::find_face(int32_t a, int32_t b, int32_t c, int* k) const {
  return find_face(a, b, c, k, seq_.around);
}

void Delaunay3D::edge_ring(int32_t t, int32_t a, int32_t b, std::vector<int32_t>& ring_tets,
                           std::vector<int32_t>& ring_verts) const {
  vm::edge_ring(topo_, t, a, b, ring_tets, ring_verts, {false, tet_capacity() + 1});
}

// ---------------------------------------------------------------- flips

bool Delaunay3D::new_tet_valid(const std::array<int32_t, 4>& q,
                               const std::vector<int32_t>& around) const {
  const int g = inf_slot(q.data());
  if (g < 0) return orient3d(point(q[0]), point(q[1]), point(q[2]), point(q[3])) < 0;
  // A ghost: its hull face is a proper triangle and no vertex of the
  // region is beyond it (the hull stays convex).
  const double* f[3];
  for (int s = 0, m = 0; s < 4; ++s)
    if (s != g) f[m++] = point(q[size_t(s)]);
  if (collinear(f[0], f[1], f[2])) return false;
  const double* c[4];
  for (int s = 0; s < 4; ++s) c[s] = s == g ? nullptr : point(q[size_t(s)]);
  for (int32_t w : around) {
    if (w == q[0] || w == q[1] || w == q[2] || w == q[3]) continue;
    c[g] = point(w);
    if (orient3d(c[0], c[1], c[2], c[3]) < 0) return false;
  }
  return true;
}

Result<std::vector<int32_t>> Delaunay3D::replace_tets(
    const std::vector<int32_t>& old_tets, const std::vector<std::array<int32_t, 4>>& new_tets) {
  using R = Result<std::vector<int32_t>>;
  if (old_tets.empty() || new_tets.empty()) return R::Error("replace_tets: empty set");
  for (int32_t t : old_tets)
    if (t < 0 || size_t(t) >= tet_capacity() || !is_live(t))
      return R::Error("replace_tets: an old tetrahedron is not live");
  // Phase 1: orientation of the new set (a ghost: its hull face against
  // the vertices of the old set).
  std::vector<int32_t> old_vertices;
  for (int32_t t : old_tets)
    for (int s = 0; s < 4; ++s)
      if (tet(t)[s] != kInfinite) old_vertices.push_back(tet(t)[s]);
  std::sort(old_vertices.begin(), old_vertices.end());
  old_vertices.erase(std::unique(old_vertices.begin(), old_vertices.end()), old_vertices.end());
  for (const auto& q : new_tets) {
    int infs = 0;
    for (int32_t x : q) {
      if (x == kInfinite) {
        ++infs;
        continue;
      }
      if (x < 0 || size_t(x) >= num_vertices())
        return R::Error("replace_tets: a new tetrahedron has an invalid vertex");
    }
    if (infs > 1 || !new_tet_valid(q, old_vertices))
      return R::Error("replace_tets: a new tetrahedron is not positive");
  }
  // Phase 2: face matching and commit.
  std::vector<int32_t> ids;
  switch (vm::replace_tets(topo_, old_tets.data(), int(old_tets.size()), new_tets.data(),
                           int(new_tets.size()), ids, replace_scratch_)) {
    case ReplaceError::kNone:
      break;
    case ReplaceError::kConstrainedInside:
      return R::Error("replace_tets: would remove a constrained face");
    case ReplaceError::kUnmatchedFace:
      return R::Error("replace_tets: the new set does not fill the old one");
    case ReplaceError::kUncoveredFace:
      return R::Error("replace_tets: the new set leaves a boundary face uncovered");
    case ReplaceError::kNoRoom:  // only with a slot pool
      return R::Error("replace_tets: no free slot");
  }
  seq_.last = ids[0];
  delaunay_ = false;
  ++seq_.stats.flips;
  return ids;
}

Result<std::array<int32_t, 3>> Delaunay3D::flip23(int32_t t, int k) {
  using R = Result<std::array<int32_t, 3>>;
  if (t < 0 || size_t(t) >= tet_capacity() || !is_live(t) || k < 0 || k > 3)
    return R::Error("flip23: invalid face");
  const int32_t u = neighbor(t, k) >> 2;
  if (is_ghost(t) || is_ghost(u)) return R::Error("flip23: a hull face");
  std::vector<std::array<int32_t, 4>> nt(3);
  flip23_tets(topo_, t, k, nt.data());
  auto res = replace_tets({t, u}, nt);
  if (!res.ok()) return R::Error("flip23: " + res.message());
  return std::array<int32_t, 3>{res.value()[0], res.value()[1], res.value()[2]};
}

Result<std::vector<int32_t>> Delaunay3D::remove_edge(int32_t t, int32_t a, int32_t b) {
  using R = Result<std::vector<int32_t>>;
  if (t < 0 || size_t(t) >= tet_capacity() || !is_live(t) || slot_of(tet(t), a) < 0 ||
      slot_of(tet(t), b) < 0 || a == b)
    return R::Error("remove_edge: (a, b) is not an edge of t");
  std::vector<int32_t> ring_tets, ring;
  edge_ring(t, a, b, ring_tets, ring);
  if (a == kInfinite || b == kInfinite) return R::Error("remove_edge: an edge at infinity");
  std::vector<int32_t> around = ring;
  around.insert(around.end(), {a, b});
  around.erase(std::remove(around.begin(), around.end(), kInfinite), around.end());
  const size_t n = ring.size();
  if (n < 3) return R::Error("remove_edge: fewer than 3 tetrahedra around the edge");
  // Fans from each ring vertex; ring order makes (a, b, r_i, r_i+1)
  // positive, hence (r_x, r_y, r_z, b) and (r_y, r_x, r_z, a) for a
  // triangle (x, y, z) in ring order.
  std::vector<std::array<int32_t, 4>> best, cand;
  double best_q = 0;
  for (size_t s = 0; s < (n == 3 ? 1 : n); ++s) {
    cand.clear();
    double q = 1e300;
    for (size_t i = 1; i + 1 < n; ++i) {
      const int32_t x = ring[s], y = ring[(s + i) % n], z = ring[(s + i + 1) % n];
      cand.resize(cand.size() + 2);
      ring_triangle_tets(a, b, x, y, z, &cand[cand.size() - 2]);
    }
    for (const auto& c : cand) {
      if (!new_tet_valid(c, around)) {
        q = -1;
        break;
      }
      if (inf_slot(c.data()) >= 0) continue;  // ghosts: no shape
      const double* p[4] = {point(c[0]), point(c[1]), point(c[2]), point(c[3])};
      double vol = -((p[1][0] - p[0][0]) * ((p[2][1] - p[0][1]) * (p[3][2] - p[0][2]) -
                                            (p[2][2] - p[0][2]) * (p[3][1] - p[0][1])) -
                     (p[1][1] - p[0][1]) * ((p[2][0] - p[0][0]) * (p[3][2] - p[0][2]) -
                                            (p[2][2] - p[0][2]) * (p[3][0] - p[0][0])) +
                     (p[1][2] - p[0][2]) * ((p[2][0] - p[0][0]) * (p[3][1] - p[0][1]) -
                                            (p[2][1] - p[0][1]) * (p[3][0] - p[0][0])));
      double longest = 0;
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          double d2 = 0;
          for (int m = 0; m < 3; ++m) d2 += (p[i][m] - p[j][m]) * (p[i][m] - p[j][m]);
          longest = std::max(longest, d2);
        }
      q = std::min(q, std::fabs(vol) / (longest * std::sqrt(longest)));
    }
    if (q > best_q || (best.empty() && q >= 0)) {
      best_q = q;
      best = cand;
    }
  }
  if (best.empty()) return R::Error("remove_edge: no fan of the ring gives positive tetrahedra");
  auto res = replace_tets(ring_tets, best);
  if (!res.ok()) return R::Error("remove_edge: " + res.message());
  return res;
}

Status Delaunay3D::flip_ring(const char* name, int32_t t, int32_t a, int32_t b, size_t n,
                             std::vector<int32_t>& ring_tets, std::vector<int32_t>& ring) const {
  if (t < 0 || size_t(t) >= tet_capacity() || !is_live(t) || slot_of(tet(t), a) < 0 ||
      slot_of(tet(t), b) < 0 || a == b)
    return Status::Error(std::string(name) + ": (a, b) is not an edge of t");
  edge_ring(t, a, b, ring_tets, ring);
  if (ring.size() != n)
    return Status::Error(std::string(name) + ": the edge is not in exactly " + std::to_string(n) +
                         " tetrahedra");
  return Status::Ok();
}

Result<std::array<int32_t, 2>> Delaunay3D::flip32(int32_t t, int32_t a, int32_t b) {
  using R = Result<std::array<int32_t, 2>>;
  std::vector<int32_t> ring_tets, ring;
  if (Status st = flip_ring("flip32", t, a, b, 3, ring_tets, ring); !st.ok()) return st;
  auto res = remove_edge(t, a, b);
  if (!res.ok()) return R::Error(res.message());
  return std::array<int32_t, 2>{res.value()[0], res.value()[1]};
}

Result<std::array<int32_t, 4>> Delaunay3D::flip44(int32_t t, int32_t a, int32_t b, int32_t c) {
  using R = Result<std::array<int32_t, 4>>;
  std::vector<int32_t> ring_tets, ring;
  if (Status st = flip_ring("flip44", t, a, b, 4, ring_tets, ring); !st.ok()) return st;
  auto it = std::find(ring.begin(), ring.end(), c);
  if (it == ring.end() || c == kInfinite)
    return R::Error("flip44: c is not a finite vertex on the ring of the edge");
  const size_t s = size_t(it - ring.begin());
  std::vector<std::array<int32_t, 4>> nt;
  for (size_t i = 1; i <= 2; ++i) {
    const int32_t x = ring[s], y = ring[(s + i) % 4], z = ring[(s + i + 1) % 4];
    nt.resize(nt.size() + 2);
    ring_triangle_tets(a, b, x, y, z, &nt[nt.size() - 2]);
  }
  auto res = replace_tets(ring_tets, nt);
  if (!res.ok()) return R::Error("flip44: " + res.message());
  const auto& ids = res.value();
  return std::array<int32_t, 4>{ids[0], ids[1], ids[2], ids[3]};
}

// ---------------------------------------------------------------- checks

Status Delaunay3D::check(bool delaunay) const {
  if (Status s = check_topology(topo_, num_vertices(), true, false); !s.ok()) return s;
  auto fail = [](const std::string& what, int32_t t) {
    return Status::Error(what + " (tetrahedron " + std::to_string(t) + ")");
  };
  for (int32_t t = 0; t < int32_t(tet_capacity()); ++t) {
    if (!is_live(t)) continue;
    const int32_t* v = tet(t);
    int infs = 0;
    for (int k = 0; k < 4; ++k) {
      if (v[k] == kInfinite) {
        ++infs;
        continue;
      }
      if (dup_[size_t(v[k])] >= 0) return fail("a duplicate point is a vertex", t);
    }
    if (infs == 0 && orient3d(point(v[0]), point(v[1]), point(v[2]), point(v[3])) >= 0)
      return fail("finite tetrahedron not positive", t);
    for (int k = 0; k < 4; ++k) {
      const int32_t e = neighbor(t, k);
      const int32_t u = e >> 2, j = e & 3;
      const int32_t* w = tet(u);
      if (v[k] == w[j]) return fail("two tetrahedra with the same vertices", t);
      if (infs == 1 && v[k] == kInfinite) {
        // The finite neighbor's apex is on the inner side of the hull face.
        int32_t q[4];
        std::copy(v, v + 4, q);
        q[k] = w[j];
        if (orient3d(point(q[0]), point(q[1]), point(q[2]), point(q[3])) <= 0)
          return fail("ghost tetrahedron wrongly oriented", t);
      }
      if (delaunay && infs == 0 && w[j] != kInfinite && !is_constrained(t, k) &&
          finite_conflict(t, point(w[j]), w[j]))
        return fail("face not locally Delaunay", t);
      if (delaunay && infs == 1 && v[k] != kInfinite && w[j] != kInfinite &&
          conflict(t, point(w[j]), w[j], true))
        return fail("convex hull not convex", t);
    }
  }
  return Status::Ok();
}

}  // namespace vm
