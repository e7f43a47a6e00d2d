// The insertion kernel of Delaunay3D: Bowyer-Watson (Bowyer, "Computing
// Dirichlet tessellations", Comput. J. 24, 1981; Watson, "Computing the
// n-dimensional Delaunay tessellation with application to Voronoi
// polytopes", Comput. J. 24, 1981) after a remembering stochastic
// visibility walk (Devillers, Pion, Teillaud, "Walking in a triangulation",
// IJFCS 13, 2002), with Shewchuk's filtered exact predicates (DCG 18, 1997)
// and insphere ties broken by symbolic perturbation (Edelsbrunner, Muecke
// 1990). See delaunay3d.h for the data layout.
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
// Predicates: a static filter bound from the vertices' box, then the
// semi-static one, then the exact predicate (core/geom/predicates.h).
#include <algorithm>
#include <cmath>

#include "core/geom/predicates.h"
#include "core/volume/delaunay3d.h"
#include "core/volume/delaunay3d_internal.h"

namespace vm {
namespace {

// Bound on the cavity of the non-Delaunay / constrained insertion (so that
// an insertion stays local).
constexpr size_t kMaxCavity = 512;

// kOther[f][j]: the two slots other than f and j (f != j).
constexpr int kOther[4][4][2] = {{{-1, -1}, {2, 3}, {1, 3}, {1, 2}},
                                 {{2, 3}, {-1, -1}, {0, 3}, {0, 2}},
                                 {{1, 3}, {0, 3}, {-1, -1}, {0, 1}},
                                 {{1, 2}, {0, 2}, {0, 1}, {-1, -1}}};

}  // namespace

using delaunay3d_detail::collinear;
using delaunay3d_detail::inf_slot;
using delaunay3d_detail::same_point;

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

}  // namespace vm
