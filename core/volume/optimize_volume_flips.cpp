// The flip pass of the volume optimizer (optimize_volume.h): 2-3 face
// removal and edge removal (Shewchuk, "Two discrete optimization
// algorithms for the topological improvement of tetrahedral meshes", 2002;
// Klingner and Shewchuk, "Aggressive tetrahedral mesh improvement", IMR
// 2007), the ring of a removed edge re-triangulated by Klincsek's dynamic
// program ("Minimal triangulations of polygonal domains", 1980) maximizing
// the smallest gamma_t (core/volume/edge_removal.h, shared with the
// Delaunay kernel's edge removal). A change is made only when it raises the smallest
// quality of the tetrahedra it replaces. A pass on many tetrahedra runs on
// kParts slabs of vertices at the same time (on the threads), then
// sequentially on what crosses slabs: parallel_flips() says why no slab
// reads what another writes.
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "core/geom/predicates.h"
#include "core/geom/vec3.h"
#include "core/quality/tet_quality.h"
#include "core/util/parallel.h"
#include "core/volume/edge_removal.h"
#include "core/volume/optimize_volume_internal.h"
#include "core/volume/tet_topology.h"

namespace vm {
namespace optimize_volume_detail {
namespace {

// Edges of a tetrahedron tried for removal before the shorter ones.
constexpr int kLongEdges = 3;
// Flip passes on fewer tetrahedra run sequentially.
constexpr size_t kMinParallelFlips = 4096;

using v3::cross;
using v3::dot;
using v3::sub;

OptimizeStats& stats_of(Optimizer& op, FlipWork& w) { return w.part < 0 ? op.stats : w.counts; }

// The triangulation of the ring of edge (a, b) (ring vertex ids, at most
// kMaxRing) maximizing the smallest gamma_t of its tetrahedra pairs
// (x, y, z, b), (y, x, z, a), among every triangulation (Klincsek's
// dynamic program, core/volume/edge_removal.h). Returns that quality
// (stops early, returning something <= floor, when it cannot beat floor);
// triangles into tris. gamma_t of a triangle's two tetrahedra shares their
// face (x, y, z): the squared lengths and the areas of the faces through a
// or b are computed once per pair of ring vertices (lazily) instead of
// once per tetrahedron, and the second tetrahedron is not measured when
// the first is already no better than the bound.
double best_ring_gamma(Optimizer& op, int32_t a, int32_t b, const std::vector<int32_t>& ring,
                       double floor, std::vector<RingTriangle>* tris) {
  const int n = int(ring.size());
  const double* pa = op.m.point(a);
  const double* pb = op.m.point(b);
  const double* P[kMaxRing];
  double da[kMaxRing], db[kMaxRing];  // squared distances to a and b
  for (int i = 0; i < n; ++i) {
    P[i] = op.m.point(ring[size_t(i)]);
    double d[3];
    sub(P[i], pa, d);
    da[i] = dot(d, d);
    sub(P[i], pb, d);
    db[i] = dot(d, d);
  }
  // Per pair i < k: squared length, twice the areas of (i, k, a), (i, k, b).
  double len2[kMaxRing][kMaxRing], fa[kMaxRing][kMaxRing], fb[kMaxRing][kMaxRing];
  for (int i = 0; i < n; ++i)
    for (int k = i + 1; k < n; ++k) len2[i][k] = -1;
  auto pair = [&](int i, int k) {
    if (len2[i][k] < 0) {
      double u[3], w[3], c[3];
      sub(P[k], P[i], u);
      len2[i][k] = dot(u, u);
      sub(P[i], pa, u), sub(P[k], pa, w), cross(u, w, c);
      fa[i][k] = std::sqrt(dot(c, c));
      sub(P[i], pb, u), sub(P[k], pb, w), cross(u, w, c);
      fb[i][k] = std::sqrt(dot(c, c));
    }
  };
  constexpr double kSqrt6 = 2.449489742783178;
  auto gamma = [&](int i, int k, int j, double bound) {
    // Triangle (x, y, z) = ring (i, k, j); n = (y - x) x (z - x).
    double u[3], w[3], nr[3], d[3];
    sub(P[k], P[i], u), sub(P[j], P[i], w), cross(u, w, nr);
    sub(pb, P[i], d);
    const double vol_b = dot(nr, d);
    if (!(vol_b > 0)) return -HUGE_VAL;
    pair(i, k), pair(k, j), pair(i, j);
    const double area = std::sqrt(dot(nr, nr));
    const double lmax = std::max({len2[i][k], len2[k][j], len2[i][j]});
    const double den_b = 0.5 * (area + fb[i][k] + fb[k][j] + fb[i][j]) *
                         std::sqrt(std::max({lmax, db[i], db[k], db[j]}));
    const double q = den_b > 0 ? kSqrt6 * vol_b / den_b : 0;
    if (q <= bound) return q;
    sub(pa, P[i], d);
    const double vol_a = -dot(nr, d);
    const double den_a = 0.5 * (area + fa[i][k] + fa[k][j] + fa[i][j]) *
                         std::sqrt(std::max({lmax, da[i], da[k], da[j]}));
    return std::min(q, den_a > 0 ? kSqrt6 * vol_a / den_a : 0);
  };
  return best_ring_triangulation(n, RingCandidates::kAll, floor, gamma, tris);
}

}  // namespace

Flip improve_topology(Optimizer& op, int32_t t, FlipWork& w) {
  ++stats_of(op, w).topology_attempts;
  double best_gain = 0;
  int best_kind = 0;  // 1: face removal, 2: edge removal
  int best_arg = -1;
  const int32_t* v = op.m.tet(t);
  // 2-3 on each interior face.
  for (int k = 0; k < 4; ++k) {
    if (op.m.is_constrained(t, k)) continue;
    const int32_t u = op.m.neighbor(t, k) >> 2;
    std::array<int32_t, 4> q[3];
    flip23_tets(op.m.topology(), t, k, q);
    const double old_min = std::min(op.cached(t), op.cached(u));
    double new_min = 1e300;
    for (int i = 0; i < 3 && new_min > old_min; ++i)
      new_min = std::min(new_min, tet_gamma(op.m.point(q[i][0]), op.m.point(q[i][1]),
                                            op.m.point(q[i][2]), op.m.point(q[i][3])));
    if (new_min - old_min > best_gain) {
      best_gain = new_min - old_min;
      best_kind = 1;
      best_arg = k;
    }
  }
  // Removal of each edge, longest first (the diagonals of a sliver), the
  // dynamic program only looking for more than the best gain so far. The
  // three shorter edges are tried only when nothing else gained: they
  // give 4% of the changes on the aortic arch, and skipping them when
  // another change exists costs no quality there.
  int edges[6];
  double len2[6];
  for (int e = 0; e < 6; ++e) {
    edges[e] = e;
    double d[3];
    sub(op.m.point(v[kTetEdges[e][0]]), op.m.point(v[kTetEdges[e][1]]), d);
    len2[e] = dot(d, d);
  }
  std::sort(edges, edges + 6, [&](int x, int y) { return len2[x] > len2[y]; });
  for (int rank = 0; rank < 6; ++rank) {
    if (rank == kLongEdges && best_kind != 0) break;
    const int e = edges[rank];
    const int32_t a = v[kTetEdges[e][0]], b = v[kTetEdges[e][1]];
    if (!op.m.edge_ring(t, a, b, w.ring_tets, w.ring, kMaxRing)) continue;
    const int n = int(w.ring.size());
    if (n < 3) continue;
    double old_min = 1e300;
    for (int32_t u : w.ring_tets) old_min = std::min(old_min, op.cached(u));
    const double new_min = best_ring_gamma(op, a, b, w.ring, old_min + best_gain, nullptr);
    if (new_min - old_min > best_gain) {
      best_gain = new_min - old_min;
      best_kind = 2;
      best_arg = e;
    }
  }
  if (best_kind == 0 || best_gain < 1e-9) return Flip::kNone;
  std::array<int32_t, 4> nt[2 * kMaxRing];
  if (best_kind == 1) {
    flip23_tets(op.m.topology(), t, best_arg, nt);
    w.old[0] = t, w.old[1] = op.m.neighbor(t, best_arg) >> 2;
    const Flip r = commit(op, w, w.old, 2, nt, 3);
    if (r == Flip::kDone) ++stats_of(op, w).flips23;
    return r;
  }
  const int32_t a = v[kTetEdges[best_arg][0]], b = v[kTetEdges[best_arg][1]];
  op.m.edge_ring(t, a, b, w.ring_tets, w.ring, kMaxRing);
  if (!(best_ring_gamma(op, a, b, w.ring, 0, &w.tris) > 0)) return Flip::kNone;
  ring_removal_tets(a, b, w.ring.data(), w.tris, nt);
  const int n_new = 2 * int(w.tris.size());
  for (size_t i = 0; i < w.ring_tets.size(); ++i) w.old[i] = w.ring_tets[i];
  const Flip r = commit(op, w, w.old, int(w.ring_tets.size()), nt, n_new);
  if (r == Flip::kDone) ++stats_of(op, w).edge_removals;
  return r;
}

Flip commit(Optimizer& op, FlipWork& w, const int32_t* old, int n_old,
            const std::array<int32_t, 4>* nt, int n_new) {
  for (int i = 0; i < n_new; ++i)
    if (orient3d(op.m.point(nt[i][0]), op.m.point(nt[i][1]), op.m.point(nt[i][2]),
                 op.m.point(nt[i][3])) >= 0)
      return Flip::kNone;
  if (w.part >= 0) {
    for (int i = 0; i < n_old; ++i)
      for (int k = 0; k < 4; ++k)
        if (op.vpart[size_t(op.m.tet(old[i])[k])] != w.part) return Flip::kDeferred;
    switch (op.m.replace_in(old, n_old, nt, n_new, w.ids, w.replace, w.pool)) {
      case ReplaceError::kNone:
        break;
      case ReplaceError::kNoRoom:
        return Flip::kDeferred;
      default:
        return Flip::kNone;
    }
  } else {
    if (!op.m.replace(old, n_old, nt, n_new, &w.ids)) return Flip::kNone;
    if (op.q.size() < op.m.capacity())
      op.q.resize(op.m.capacity(), 2.0), op.dirty.resize(op.m.capacity(), 0);
  }
  for (int i = n_new; i < n_old; ++i) op.q[size_t(old[i])] = 2.0;
  for (int32_t id : w.ids) {
    op.q[size_t(id)] = op.quality(id);
    if (w.part < 0)
      op.mark(id);
    else if (!op.dirty[size_t(id)])
      op.dirty[size_t(id)] = 1, w.touched.push_back(id);
    w.created.push_back(id);
  }
  return Flip::kDone;
}

namespace {

// Flips on the tetrahedra of `work` in order, and on those the changes
// create below threshold (appended), at most 20 times the list's
// length; those w defers into w.later.
void flip_list(Optimizer& op, FlipWork& w, std::vector<int32_t>& work, double threshold) {
  const size_t limit = 20 * work.size() + 1000;
  for (size_t i = 0; i < work.size() && i < limit; ++i) {
    const int32_t t = work[i];
    if (!op.m.is_live(t) || op.cached(t) >= threshold) continue;
    w.created.clear();
    const Flip r = improve_topology(op, t, w);
    if (r == Flip::kDeferred) w.later.push_back(t);
    if (r != Flip::kDone) continue;
    for (int32_t u : w.created)
      if (op.cached(u) < threshold) work.push_back(u);
  }
}

// The slabs' part of a flip pass on op.work (ascending ids): each slab of
// vertex_slabs() works through the tetrahedra of op.work with all their
// vertices in it (and those its changes create below threshold), at the
// same time as the others, changing only tetrahedra of its own; what
// needs another slab's is left in op.work, for the sequential rest. A slab
// never writes what another reads (a tetrahedron next to one of its
// slab's, or around one of its edges, has three or two vertices in it),
// so the mesh does not depend on the thread count.
void parallel_flips(Optimizer& op, double threshold) {
  op.vpart = vertex_slabs(op, kParts);
  std::vector<FlipWork> fw(kParts);
  std::vector<int32_t> later;
  for (int32_t t : op.work) {
    const int32_t* v = op.m.tet(t);
    const uint8_t j = op.vpart[size_t(v[0])];
    if (op.vpart[size_t(v[1])] == j && op.vpart[size_t(v[2])] == j && op.vpart[size_t(v[3])] == j)
      fw[j].work.push_back(t);
    else
      later.push_back(t);
  }
  // Slots: a change adds at most kMaxRing - 4 tetrahedra (a ring of n
  // gives 2 n - 4), but most remove one (3-2) and each slab reuses the
  // slots it frees (aortic arch: 9,000 freed per slab, 15 more needed at
  // most); a slab without a free slot defers the change.
  std::vector<SlotPool> pools;
  op.m.take_slot_pools(std::vector<size_t>(kParts, 64), pools);
  for (size_t j = 0; j < kParts; ++j) fw[j].part = int(j), fw[j].pool = std::move(pools[j]);
  parallel_for(kParts, 1, [&](size_t begin, size_t end) {
    for (size_t j = begin; j < end; ++j) flip_list(op, fw[j], fw[j].work, threshold);
  });
  for (size_t j = 0; j < kParts; ++j) {
    FlipWork& w = fw[j];
    pools[j] = std::move(w.pool);
    op.stats.topology_attempts += w.counts.topology_attempts;
    op.stats.flips23 += w.counts.flips23;
    op.stats.edge_removals += w.counts.edge_removals;
    op.touched.insert(op.touched.end(), w.touched.begin(), w.touched.end());
    later.insert(later.end(), w.later.begin(), w.later.end());
  }
  op.m.return_slot_pools(pools);
  std::sort(later.begin(), later.end());
  later.erase(std::unique(later.begin(), later.end()), later.end());
  op.work = std::move(later);
}

}  // namespace

// Flips on every tetrahedron below threshold until none improves. Only
// tetrahedra created or moved since the last pass are tried (dirty):
// the others already failed with the same neighbors, nearly always.
// worst_first: in increasing quality, else in id order (neighbors have
// nearby ids, so the many changes of a first pass stay in cache; on the
// aortic arch: 30% less time there, the same mean quality).
void flip_pass(Optimizer& op, double threshold, bool worst_first) {
  op.work.clear();
  if (op.all_dirty || op.touched.size() > op.m.capacity() / 8) {
    for (int32_t t = 0; t < int32_t(op.m.capacity()); ++t)
      if (op.m.is_live(t) && op.cached(t) < threshold && op.dirty[size_t(t)]) op.work.push_back(t);
    std::fill(op.dirty.begin(), op.dirty.end(), 0);
  } else {
    for (int32_t t : op.touched) {
      if (op.m.is_live(t) && op.cached(t) < threshold) op.work.push_back(t);
      op.dirty[size_t(t)] = 0;
    }
    std::sort(op.work.begin(), op.work.end());
  }
  op.all_dirty = false;
  op.touched.clear();
  if (worst_first)
    std::sort(op.work.begin(), op.work.end(), [&](int32_t a, int32_t b) {
      return op.cached(a) < op.cached(b) || (op.cached(a) == op.cached(b) && a < b);
    });
  if (!worst_first && op.work.size() >= kMinParallelFlips) parallel_flips(op, threshold);
  flip_list(op, op.fseq, op.work, threshold);
}

}  // namespace optimize_volume_detail
}  // namespace vm
