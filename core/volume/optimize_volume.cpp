// Tetrahedral mesh improvement: flips and edge removal maximizing the
// smallest gamma_t (Shewchuk 2002; Klingner and Shewchuk 2007; ring
// triangulations by Klincsek 1980), smart smoothing toward an ODT-like
// position (Freitag and Ollivier-Gooch 1997; Chen and Xu 2004; Alliez,
// Cohen-Steiner, Yvinec and Desbrun 2005) and a sliver phase climbing the
// worst quality; see optimize_volume.h.
//
// Phases: (1) qualities of every tetrahedron (cached per slot); (2) `passes`
// rounds of flips on the tetrahedra below flip_threshold (in id order, for
// memory locality) then smoothing of every free vertex, and one more round
// of flips; (3) the sliver phase (worst first); (4) statistics from the
// cached qualities. The flip and smoothing rounds of (2) run on eight slabs
// of vertices at the same time (on the threads), then sequentially on what
// crosses slabs: parallel_flips() and smooth_pass() say why no slab reads
// what another writes.
#include "core/volume/optimize_volume.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "core/geom/predicates.h"
#include "core/geom/vec3.h"
#include "core/quality/tet_quality.h"
#include "core/util/parallel.h"
#include "core/util/stage_timer.h"
#include "core/volume/slabs.h"
#include "core/volume/tet_topology.h"

namespace vm {
namespace {

constexpr int kMaxRing = 8;
constexpr int kMaxCavity = 24;
// Edges of a tetrahedron tried for removal before the shorter ones.
constexpr int kLongEdges = 3;
// Smallest quality a smoothing move may create (below it the exact
// orientation test decides anyway; this keeps the search off flat shapes).
constexpr double kGuard = 1e-3;
// Slabs of a parallel smoothing or flip pass: fixed, so that the mesh does
// not depend on the thread count.
constexpr size_t kParts = 8;
// Flip passes on fewer tetrahedra run sequentially.
constexpr size_t kMinParallelFlips = 4096;

using v3::cross;
using v3::dot;
using v3::sub;

// Circumcenter of a tetrahedron and its signed volume times 6 (> 0:
// positive); false when (nearly) flat.
inline bool circumcenter(const double* a, const double* b, const double* c, const double* d,
                         double* o, double* vol6) {
  double u[3], v[3], w[3];
  sub(b, a, u), sub(c, a, v), sub(d, a, w);
  double vw[3], wu[3], uv[3];
  cross(v, w, vw), cross(w, u, wu), cross(u, v, uv);
  *vol6 = dot(u, vw);
  if (*vol6 == 0) return false;
  const double inv = 0.5 / *vol6;
  const double uu = dot(u, u), vv = dot(v, v), ww = dot(w, w);
  for (int k = 0; k < 3; ++k) o[k] = a[k] + (uu * vw[k] + vv * wu[k] + ww * uv[k]) * inv;
  return std::isfinite(o[0]) && std::isfinite(o[1]) && std::isfinite(o[2]);
}

// A read-only view of tetrahedron ids.
class Span {
 public:
  Span(const int32_t* p, size_t n) : p_(p), n_(n) {}
  explicit Span(const std::vector<int32_t>& v) : p_(v.data()), n_(v.size()) {}
  const int32_t* begin() const { return p_; }
  const int32_t* end() const { return p_ + n_; }
  size_t size() const { return n_; }

 private:
  const int32_t* p_;
  size_t n_;
};

class Optimizer {
 public:
  Optimizer(TetMesh& mesh, const std::vector<double>& h, const OptimizeOptions& options,
            OptimizeStats& stats)
      : m_(mesh), h_(h), opt_(options), st_(stats), rng_(options.seed) {}

  const std::vector<double>& sizes() const { return h_; }

  void compute_all_qualities() {
    q_.assign(m_.capacity(), 2.0);
    dirty_.assign(m_.capacity(), 1);
    all_dirty_ = true;
    touched_.clear();
    parallel_for(m_.capacity(), 1 << 14, [&](size_t begin, size_t end) {
      for (size_t t = begin; t < end; ++t)
        if (m_.is_live(int32_t(t))) q_[t] = quality(int32_t(t));
    });
  }

  double quality(int32_t t) const {
    const int32_t* v = m_.tet(t);
    return tet_gamma(m_.point(v[0]), m_.point(v[1]), m_.point(v[2]), m_.point(v[3]));
  }
  double cached(int32_t t) const { return q_[size_t(t)]; }

  // Statistics of the cached qualities of the live tetrahedra (the formula
  // of tet_qualities(), clamped to [-1, 1] as there).
  QualityStats stats() const {
    std::vector<float> q;
    q.reserve(m_.num_tets());
    for (int32_t t = 0; t < int32_t(m_.capacity()); ++t)
      if (m_.is_live(t)) q.push_back(float(std::clamp(cached(t), -1.0, 1.0)));
    return quality_stats(q, 20);
  }

  // ---------------------------------------------------------------- flips

  // What a topological change did.
  enum class Flip { kNone, kDone, kDeferred };

  // A flip worker: the sequential one (part -1: the mesh's own free list,
  // the optimizer's statistics and dirty list) or a slab's of a parallel
  // flip pass (its own slot pool, statistics and dirty list).
  struct FlipWork {
    int part = -1;
    SlotPool pool;
    ReplaceScratch replace;
    std::vector<int32_t> ring_tets, ring, ids, created, work, later, touched;
    std::vector<std::array<int, 3>> tris;
    int32_t old[64];
    OptimizeStats counts;
  };

  // Best topological change around tetrahedron t (2-3 on one of its faces
  // or removal of one of its edges) that raises the smallest quality of the
  // tetrahedra it replaces; applied if found (kDone). New ids into
  // w.created. A slab's worker reads only t, its neighbors and the
  // tetrahedra around its edges, and defers (kDeferred, nothing changed) a
  // change that would replace a tetrahedron with a vertex outside its slab.
  Flip improve_topology(int32_t t, FlipWork& w) {
    ++stats_of(w).topology_attempts;
    double best_gain = 0;
    int best_kind = 0;  // 1: face removal, 2: edge removal
    int best_arg = -1;
    const int32_t* v = m_.tet(t);
    // 2-3 on each interior face.
    for (int k = 0; k < 4; ++k) {
      if (m_.is_constrained(t, k)) continue;
      const int32_t u = m_.neighbor(t, k) >> 2;
      std::array<int32_t, 4> q[3];
      flip23_tets(m_.topology(), t, k, q);
      const double old_min = std::min(cached(t), cached(u));
      double new_min = 1e300;
      for (int i = 0; i < 3 && new_min > old_min; ++i)
        new_min = std::min(new_min, tet_gamma(m_.point(q[i][0]), m_.point(q[i][1]),
                                              m_.point(q[i][2]), m_.point(q[i][3])));
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
      sub(m_.point(v[kTetEdges[e][0]]), m_.point(v[kTetEdges[e][1]]), d);
      len2[e] = dot(d, d);
    }
    std::sort(edges, edges + 6, [&](int x, int y) { return len2[x] > len2[y]; });
    for (int rank = 0; rank < 6; ++rank) {
      if (rank == kLongEdges && best_kind != 0) break;
      const int e = edges[rank];
      const int32_t a = v[kTetEdges[e][0]], b = v[kTetEdges[e][1]];
      if (!m_.edge_ring(t, a, b, w.ring_tets, w.ring, kMaxRing)) continue;
      const int n = int(w.ring.size());
      if (n < 3) continue;
      double old_min = 1e300;
      for (int32_t u : w.ring_tets) old_min = std::min(old_min, cached(u));
      const double new_min = best_ring_triangulation(a, b, w.ring, old_min + best_gain, nullptr);
      if (new_min - old_min > best_gain) {
        best_gain = new_min - old_min;
        best_kind = 2;
        best_arg = e;
      }
    }
    if (best_kind == 0 || best_gain < 1e-9) return Flip::kNone;
    std::array<int32_t, 4> nt[2 * kMaxRing];
    int n_new = 0;
    if (best_kind == 1) {
      flip23_tets(m_.topology(), t, best_arg, nt);
      w.old[0] = t, w.old[1] = m_.neighbor(t, best_arg) >> 2;
      const Flip r = commit(w, w.old, 2, nt, 3);
      if (r == Flip::kDone) ++stats_of(w).flips23;
      return r;
    }
    const int32_t a = v[kTetEdges[best_arg][0]], b = v[kTetEdges[best_arg][1]];
    m_.edge_ring(t, a, b, w.ring_tets, w.ring, kMaxRing);
    if (!(best_ring_triangulation(a, b, w.ring, 0, &w.tris) > 0)) return Flip::kNone;
    for (const auto& tri : w.tris) {
      ring_triangle_tets(a, b, w.ring[size_t(tri[0])], w.ring[size_t(tri[1])],
                         w.ring[size_t(tri[2])], nt + n_new);
      n_new += 2;
    }
    for (size_t i = 0; i < w.ring_tets.size(); ++i) w.old[i] = w.ring_tets[i];
    const Flip r = commit(w, w.old, int(w.ring_tets.size()), nt, n_new);
    if (r == Flip::kDone) ++stats_of(w).edge_removals;
    return r;
  }

  OptimizeStats& stats_of(FlipWork& w) { return w.part < 0 ? st_ : w.counts; }

  // Klincsek's dynamic program over the ring polygon `ring`: the
  // triangulation maximizing the smallest quality of its tetrahedra pairs
  // (x, y, z, b), (y, x, z, a). Returns that quality (stops early, returning
  // something <= floor, when it cannot beat floor); triangles into tris.
  // A triangle (or sub-polygon) whose quality is not above floor is never
  // part of an answer above floor, so it is dropped at once; the squared
  // lengths and the areas of the faces through a or b are computed once
  // per pair of ring vertices (lazily) instead of once per tetrahedron.
  double best_ring_triangulation(int32_t a, int32_t b, const std::vector<int32_t>& ring,
                                 double floor, std::vector<std::array<int, 3>>* tris) {
    constexpr double kNone = -1e300;
    const int n = int(ring.size());
    const double* pa = m_.point(a);
    const double* pb = m_.point(b);
    const double* P[kMaxRing];
    double da[kMaxRing], db[kMaxRing];  // squared distances to a and b
    for (int i = 0; i < n; ++i) {
      P[i] = m_.point(ring[size_t(i)]);
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
    double best[kMaxRing][kMaxRing];
    int arg[kMaxRing][kMaxRing];
    for (int i = 0; i + 1 < n; ++i) best[i][i + 1] = 1e300;
    for (int len = 2; len < n; ++len)
      for (int i = 0; i + len < n; ++i) {
        const int j = i + len;
        double bij = kNone;
        int aij = -1;
        for (int k = i + 1; k < j; ++k) {
          const double sub_q = std::min(best[i][k], best[k][j]);
          if (sub_q <= bij || sub_q <= floor) continue;
          // Triangle (x, y, z) = ring (i, k, j); n = (y - x) x (z - x).
          double u[3], w[3], nr[3], d[3];
          sub(P[k], P[i], u), sub(P[j], P[i], w), cross(u, w, nr);
          sub(pb, P[i], d);
          const double vol_b = dot(nr, d);
          if (!(vol_b > 0)) continue;
          pair(i, k), pair(k, j), pair(i, j);
          const double area = std::sqrt(dot(nr, nr));
          const double lmax = std::max({len2[i][k], len2[k][j], len2[i][j]});
          const double den_b = 0.5 * (area + fb[i][k] + fb[k][j] + fb[i][j]) *
                               std::sqrt(std::max({lmax, db[i], db[k], db[j]}));
          double q = den_b > 0 ? kSqrt6 * vol_b / den_b : 0;
          if (q <= bij || q <= floor) continue;
          sub(pa, P[i], d);
          const double vol_a = -dot(nr, d);
          const double den_a = 0.5 * (area + fa[i][k] + fa[k][j] + fa[i][j]) *
                               std::sqrt(std::max({lmax, da[i], da[k], da[j]}));
          q = std::min(q, den_a > 0 ? kSqrt6 * vol_a / den_a : 0);
          q = std::min(q, sub_q);
          if (q <= bij || q <= floor) continue;
          bij = q;
          aij = k;
        }
        best[i][j] = bij;
        arg[i][j] = aij;
      }
    const double result = best[0][n - 1];
    if (tris) {
      tris->clear();
      if (result <= floor) return result;
      int stack[2 * kMaxRing][2], top = 0;
      stack[top][0] = 0, stack[top][1] = n - 1, ++top;
      while (top > 0) {
        --top;
        const int i = stack[top][0], j = stack[top][1];
        if (j - i < 2) continue;
        const int k = arg[i][j];
        tris->push_back({i, k, j});
        stack[top][0] = i, stack[top][1] = k, ++top;
        stack[top][0] = k, stack[top][1] = j, ++top;
      }
    }
    return result;
  }

  // Exact orientation of the new set, then (a slab's worker: if the old
  // tetrahedra are all in its slab, else kDeferred) the replacement and the
  // cache; new ids into w.created.
  Flip commit(FlipWork& w, const int32_t* old, int n_old, const std::array<int32_t, 4>* nt,
              int n_new) {
    for (int i = 0; i < n_new; ++i)
      if (orient3d(m_.point(nt[i][0]), m_.point(nt[i][1]), m_.point(nt[i][2]),
                   m_.point(nt[i][3])) >= 0)
        return Flip::kNone;
    if (w.part >= 0) {
      for (int i = 0; i < n_old; ++i)
        for (int k = 0; k < 4; ++k)
          if (vpart_[size_t(m_.tet(old[i])[k])] != w.part) return Flip::kDeferred;
      switch (m_.replace_in(old, n_old, nt, n_new, w.ids, w.replace, w.pool)) {
        case ReplaceError::kNone:
          break;
        case ReplaceError::kNoRoom:
          return Flip::kDeferred;
        default:
          return Flip::kNone;
      }
    } else {
      if (!m_.replace(old, n_old, nt, n_new, &w.ids)) return Flip::kNone;
      if (q_.size() < m_.capacity()) q_.resize(m_.capacity(), 2.0), dirty_.resize(m_.capacity(), 0);
    }
    for (int i = n_new; i < n_old; ++i) q_[size_t(old[i])] = 2.0;
    for (int32_t id : w.ids) {
      q_[size_t(id)] = quality(id);
      if (w.part < 0)
        mark(id);
      else if (!dirty_[size_t(id)])
        dirty_[size_t(id)] = 1, w.touched.push_back(id);
      w.created.push_back(id);
    }
    return Flip::kDone;
  }

  // Tetrahedron t was created or moved: dirty (listed once in touched_),
  // and logged when a log is on.
  void mark(int32_t t) {
    if (!dirty_[size_t(t)]) dirty_[size_t(t)] = 1, touched_.push_back(t);
    if (log_) log_->push_back(t);
  }

  // Flips on every tetrahedron below threshold until none improves. Only
  // tetrahedra created or moved since the last pass are tried (dirty):
  // the others already failed with the same neighbors, nearly always.
  // worst_first: in increasing quality, else in id order (neighbors have
  // nearby ids, so the many changes of a first pass stay in cache; on the
  // aortic arch: 30% less time there, the same mean quality).
  void flip_pass(double threshold, bool worst_first) {
    work_.clear();
    if (all_dirty_ || touched_.size() > m_.capacity() / 8) {
      for (int32_t t = 0; t < int32_t(m_.capacity()); ++t)
        if (m_.is_live(t) && cached(t) < threshold && dirty_[size_t(t)]) work_.push_back(t);
      std::fill(dirty_.begin(), dirty_.end(), 0);
    } else {
      for (int32_t t : touched_) {
        if (m_.is_live(t) && cached(t) < threshold) work_.push_back(t);
        dirty_[size_t(t)] = 0;
      }
      std::sort(work_.begin(), work_.end());
    }
    all_dirty_ = false;
    touched_.clear();
    if (worst_first)
      std::sort(work_.begin(), work_.end(), [&](int32_t a, int32_t b) {
        return cached(a) < cached(b) || (cached(a) == cached(b) && a < b);
      });
    if (!worst_first && work_.size() >= kMinParallelFlips) parallel_flips(threshold);
    flip_list(fseq_, work_, threshold);
  }

  // Flips on the tetrahedra of `work` in order, and on those the changes
  // create below threshold (appended), at most 20 times the list's
  // length; those w defers into w.later.
  void flip_list(FlipWork& w, std::vector<int32_t>& work, double threshold) {
    const size_t limit = 20 * work.size() + 1000;
    for (size_t i = 0; i < work.size() && i < limit; ++i) {
      const int32_t t = work[i];
      if (!m_.is_live(t) || cached(t) >= threshold) continue;
      w.created.clear();
      const Flip r = improve_topology(t, w);
      if (r == Flip::kDeferred) w.later.push_back(t);
      if (r != Flip::kDone) continue;
      for (int32_t u : w.created)
        if (cached(u) < threshold) work.push_back(u);
    }
  }

  // The slabs' part of a flip pass on work_ (ascending ids): each slab of
  // vertex_slabs() works through the tetrahedra of work_ with all their
  // vertices in it (and those its changes create below threshold), at the
  // same time as the others, changing only tetrahedra of its own; what
  // needs another slab's is left in work_, for the sequential rest. A slab
  // never writes what another reads (a tetrahedron next to one of its
  // slab's, or around one of its edges, has three or two vertices in it),
  // so the mesh does not depend on the thread count.
  void parallel_flips(double threshold) {
    vpart_ = vertex_slabs(kParts);
    std::vector<FlipWork> fw(kParts);
    std::vector<int32_t> later;
    for (int32_t t : work_) {
      const int32_t* v = m_.tet(t);
      const uint8_t j = vpart_[size_t(v[0])];
      if (vpart_[size_t(v[1])] == j && vpart_[size_t(v[2])] == j && vpart_[size_t(v[3])] == j)
        fw[j].work.push_back(t);
      else
        later.push_back(t);
    }
    // Slots: a change adds at most kMaxRing - 4 tetrahedra (a ring of n
    // gives 2 n - 4), but most remove one (3-2) and each slab reuses the
    // slots it frees (aortic arch: 9,000 freed per slab, 15 more needed at
    // most); a slab without a free slot defers the change.
    std::vector<SlotPool> pools;
    m_.take_slot_pools(std::vector<size_t>(kParts, 64), pools);
    for (size_t j = 0; j < kParts; ++j) fw[j].part = int(j), fw[j].pool = std::move(pools[j]);
    parallel_for(kParts, 1, [&](size_t begin, size_t end) {
      for (size_t j = begin; j < end; ++j) flip_list(fw[j], fw[j].work, threshold);
    });
    for (size_t j = 0; j < kParts; ++j) {
      FlipWork& w = fw[j];
      pools[j] = std::move(w.pool);
      st_.topology_attempts += w.counts.topology_attempts;
      st_.flips23 += w.counts.flips23;
      st_.edge_removals += w.counts.edge_removals;
      touched_.insert(touched_.end(), w.touched.begin(), w.touched.end());
      later.insert(later.end(), w.later.begin(), w.later.end());
    }
    m_.return_slot_pools(pools);
    std::sort(later.begin(), later.end());
    later.erase(std::unique(later.begin(), later.end()), later.end());
    work_ = std::move(later);
  }

  // ---------------------------------------------------------------- smoothing

  // What gamma_t of a tetrahedron (p, x, y, z) of v's star needs besides
  // p, which does not change while v moves: x, y, z (positive with p in
  // v's place), n = (y - x) x (z - x), |n|, the longest squared edge of
  // the face (x, y, z) and the sum of h at x, y, z.
  struct Opposite {
    double x[3], y[3], z[3], n[3], area2, len2, hsum;
  };

  // A smoothing's scratch: one per part of a parallel smoothing pass.
  struct StarScratch {
    std::vector<Opposite> opp;  // prepare_star()
    std::vector<double> q;      // qualities of the star at the point eval_star() tried
    int64_t moves = 0;          // smoothing moves
  };

  // The Opposite of each tetrahedron of the star S of v, for eval_star().
  void prepare_star(int32_t v, Span S, StarScratch& w) {
    w.opp.resize(S.size());
    size_t i = 0;
    for (int32_t t : S) {
      const int32_t* tv = m_.tet(t);
      int s = 0;
      while (tv[s] != v) ++s;
      const int* f = kFaceOut[s];  // (v, f) is an even permutation of (0, 1, 2, 3)
      Opposite& o = w.opp[i++];
      const double* px = m_.point(tv[f[0]]);
      const double* py = m_.point(tv[f[1]]);
      const double* pz = m_.point(tv[f[2]]);
      double u[3], w[3], e[3];
      for (int k = 0; k < 3; ++k) o.x[k] = px[k], o.y[k] = py[k], o.z[k] = pz[k];
      sub(py, px, u), sub(pz, px, w), sub(pz, py, e);
      cross(u, w, o.n);
      o.area2 = std::sqrt(dot(o.n, o.n));
      o.len2 = std::max({dot(u, u), dot(w, w), dot(e, e)});
      o.hsum = h_[size_t(tv[f[0]])] + h_[size_t(tv[f[1]])] + h_[size_t(tv[f[2]])];
    }
  }

  // Min and sum of 1/q over the star S of v with v at p; false if a
  // tetrahedron falls below kGuard (or min_required). Precondition:
  // prepare_star(v, S, w) (v may have moved since). The qualities go to
  // w.q (for move()).
  bool eval_star(Span S, const double* p, double min_required, double* qmin, double* inv_sum,
                 StarScratch& w) {
    double mn = 1e300, sum = 0;
    w.q.resize(S.size());
    for (size_t i = 0; i < S.size(); ++i) {
      const Opposite& o = w.opp[i];
      double dx[3], dy[3], dz[3], c1[3], c2[3], c3[3];
      sub(o.x, p, dx), sub(o.y, p, dy), sub(o.z, p, dz);
      cross(dx, dy, c1), cross(dy, dz, c2), cross(dz, dx, c3);
      // vol6 = (x - p) . ((y - p) x (z - p)) = (x - p) . n.
      const double vol6 = dot(dx, o.n);
      const double faces = 0.5 * (o.area2 + std::sqrt(dot(c1, c1)) + std::sqrt(dot(c2, c2)) +
                                  std::sqrt(dot(c3, c3)));
      const double l2 = std::max({o.len2, dot(dx, dx), dot(dy, dy), dot(dz, dz)});
      const double den = faces * std::sqrt(l2);
      const double q = den > 0 ? 2.449489742783178 * vol6 / den : 0;
      if (q < kGuard || q < min_required) return false;
      w.q[i] = q;
      mn = std::min(mn, q);
      sum += 1 / q;
    }
    *qmin = mn;
    *inv_sum = sum;
    return true;
  }

  bool exact_star_ok(int32_t v, Span S, const double* p) {
    for (int32_t t : S) {
      const int32_t* tv = m_.tet(t);
      const double* c[4];
      for (int k = 0; k < 4; ++k) c[k] = tv[k] == v ? p : m_.point(tv[k]);
      if (orient3d(c[0], c[1], c[2], c[3]) >= 0) return false;
    }
    return true;
  }

  // Moves v to p, the star's qualities from the eval_star() that accepted
  // p; marks the star unless `mark_later` (the caller does).
  void move(int32_t v, Span S, const double* p, const StarScratch& w, bool mark_later = false) {
    m_.set_point(v, p);
    size_t i = 0;
    for (int32_t t : S) {
      q_[size_t(t)] = w.q[i++];
      if (!mark_later) mark(t);
    }
  }

  // Smart smoothing of v toward its ODT-like position (circumcenters of the
  // star weighted by volume / h^3), falling back to the centroid of its
  // neighbors; halved steps. Returns whether v moved.
  bool smooth_vertex(int32_t v) {
    if (m_.is_fixed(v)) return false;
    m_.star(v, star_);
    const bool moved = smooth_vertex(v, Span(star_), seq_, false);
    st_.smoothing_moves += std::exchange(seq_.moves, 0);
    return moved;
  }

  // Reads and writes only v, its star's tetrahedra and their vertices'
  // positions (and w); marks nothing when `mark_later`.
  bool smooth_vertex(int32_t v, Span star, StarScratch& w, bool mark_later) {
    if (m_.is_fixed(v) || star.size() == 0) return false;
    double old_min = 1e300, old_sum = 0;
    for (int32_t t : star) {
      old_min = std::min(old_min, cached(t));
      old_sum += 1 / std::max(cached(t), 1e-12);
    }
    if (old_min >= opt_.smooth_below) return false;
    prepare_star(v, star, w);
    const double* x = m_.point(v);
    double odt[3] = {0, 0, 0}, wsum = 0, lap[3] = {0, 0, 0};
    int nlap = 0;
    // (v, x, y, z) is positive: the circumcenter from v's corner.
    for (size_t i = 0; i < star.size(); ++i) {
      const Opposite& o = w.opp[i];
      double cc[3], vol;
      if (circumcenter(x, o.x, o.y, o.z, cc, &vol) && vol > 0) {
        const double ht = 0.25 * (h_[size_t(v)] + o.hsum);
        const double w = vol / (ht * ht * ht);
        for (int k = 0; k < 3; ++k) odt[k] += w * cc[k];
        wsum += w;
      }
      for (int k = 0; k < 3; ++k) lap[k] += o.x[k] + o.y[k] + o.z[k];
      nlap += 3;
    }
    const double floor = std::min(old_min, opt_.smooth_floor);
    double targets[2][3];
    int nt = 0;
    if (wsum > 0) {
      for (int k = 0; k < 3; ++k) targets[nt][k] = odt[k] / wsum;
      ++nt;
    }
    if (nlap > 0) {
      for (int k = 0; k < 3; ++k) targets[nt][k] = lap[k] / nlap;
      ++nt;
    }
    for (int i = 0; i < nt; ++i) {
      double step = 1.0;
      for (int attempt = 0; attempt < 3; ++attempt, step *= 0.5) {
        const double p[3] = {x[0] + step * (targets[i][0] - x[0]),
                             x[1] + step * (targets[i][1] - x[1]),
                             x[2] + step * (targets[i][2] - x[2])};
        double mn, sum;
        if (!eval_star(star, p, floor, &mn, &sum, w)) continue;
        if (sum < old_sum * (1 - 1e-6) && exact_star_ok(v, star, p)) {
          move(v, star, p, w, mark_later);
          ++w.moves;
          return true;
        }
      }
    }
    return false;
  }

  // One smoothing sweep. The topology does not change during the sweep, so
  // the stars come from one vertex-to-tetrahedra incidence table (CSR)
  // instead of a search each. The vertices are cut into kParts slabs
  // of equal count along the longest axis of their box; a vertex whose
  // star's vertices are all in its own slab is interior: smoothing it reads
  // and writes nothing another slab's interior vertices do, so the slabs
  // smooth their interior vertices (each in index order) at the same time;
  // then the others the same way in kParts + 1 slabs cut halfway between
  // the first cuts; then what is left, in index order. The slabs do not
  // depend on the thread count, so neither does the mesh.
  void smooth_pass() {
    const size_t nv = m_.num_vertices();
    inc_off_.assign(nv + 1, 0);
    for (int32_t t = 0; t < int32_t(m_.capacity()); ++t)
      if (m_.is_live(t))
        for (int k = 0; k < 4; ++k) ++inc_off_[size_t(m_.tet(t)[k]) + 1];
    for (size_t v = 0; v < nv; ++v) inc_off_[v + 1] += inc_off_[v];
    inc_.resize(size_t(inc_off_[nv]));
    fill_.assign(inc_off_.begin(), inc_off_.end() - 1);
    for (int32_t t = 0; t < int32_t(m_.capacity()); ++t)
      if (m_.is_live(t))
        for (int k = 0; k < 4; ++k) inc_[size_t(fill_[size_t(m_.tet(t)[k])]++)] = t;
    auto star_of = [&](int32_t v) {
      return Span(inc_.data() + inc_off_[size_t(v)],
                  size_t(inc_off_[size_t(v) + 1] - inc_off_[size_t(v)]));
    };
    // Slab j of `part` smooths the vertices of lists[j] whose star lies in
    // it, in index order, at the same time as the other slabs; the others
    // are returned, in index order.
    auto by_slabs = [&](const std::vector<uint8_t>& part,
                        const std::vector<std::vector<int32_t>>& lists) {
      const size_t n = lists.size();
      std::vector<std::vector<int32_t>> later(n), moved(n);
      std::vector<StarScratch> scratch(n);
      parallel_for(n, 1, [&](size_t begin, size_t end) {
        for (size_t j = begin; j < end; ++j)
          for (int32_t v : lists[j]) {
            const Span star = star_of(v);
            bool interior = true;
            for (int32_t t : star)
              for (int k = 0; k < 4; ++k) interior = interior && part[size_t(m_.tet(t)[k])] == j;
            if (!interior)
              later[j].push_back(v);
            else if (smooth_vertex(v, star, scratch[j], true))
              moved[j].push_back(v);
          }
      });
      std::vector<int32_t> rest;
      for (size_t j = 0; j < n; ++j) {
        st_.smoothing_moves += scratch[j].moves;
        for (int32_t v : moved[j])
          for (int32_t t : star_of(v)) mark(t);
        rest.insert(rest.end(), later[j].begin(), later[j].end());
      }
      std::sort(rest.begin(), rest.end());
      return rest;
    };
    const std::vector<uint8_t> part = vertex_slabs(kParts);
    std::vector<std::vector<int32_t>> mine(kParts);
    for (int32_t v = 0; v < int32_t(nv); ++v) mine[part[size_t(v)]].push_back(v);
    const std::vector<int32_t> near_cuts = by_slabs(part, mine);
    // The vertices near a cut, again by slabs, whose cuts now fall halfway
    // between the first ones (so each first cut is inside one).
    const std::vector<uint8_t> part2 = vertex_slabs(kParts, true);
    std::vector<std::vector<int32_t>> mine2(kParts + 1);
    for (int32_t v : near_cuts) mine2[part2[size_t(v)]].push_back(v);
    const std::vector<int32_t> rest = by_slabs(part2, mine2);
    for (int32_t v : rest) smooth_vertex(v, star_of(v), seq_, false);
    st_.smoothing_moves += std::exchange(seq_.moves, 0);
  }

  // The slab (0 .. parts - 1) of each vertex: equal counts along the
  // longest axis of the vertices' box, ties to the same slab. halfway:
  // parts + 1 slabs, cut halfway between those cuts (at the count
  // fractions (2 j - 1) / (2 parts), j = 1 .. parts).
  std::vector<uint8_t> vertex_slabs(size_t parts, bool halfway = false) const {
    const size_t nv = m_.num_vertices();
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < nv; ++v)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], m_.point(int32_t(v))[k]);
        hi[k] = std::max(hi[k], m_.point(int32_t(v))[k]);
      }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
    std::vector<double> xs(nv);
    for (size_t v = 0; v < nv; ++v) xs[v] = m_.point(int32_t(v))[axis];
    const Slabs slabs = equal_count_slabs(xs, axis, parts, halfway);
    std::vector<uint8_t> part(nv);
    for (size_t v = 0; v < nv; ++v) part[v] = uint8_t(slabs.of(m_.point(int32_t(v))));
    return part;
  }

  // ---------------------------------------------------------------- slivers

  // Raises the smallest quality of v's star: gradient of the worst
  // tetrahedron's quality, then deterministic random perturbations.
  bool climb_vertex(int32_t v) {
    if (m_.is_fixed(v)) return false;
    m_.star(v, star_);
    if (star_.empty()) return false;
    prepare_star(v, Span(star_), seq_);
    double old_min = 1e300;
    int32_t worst = -1;
    for (int32_t t : star_)
      if (cached(t) < old_min) old_min = cached(t), worst = t;
    const double* x = m_.point(v);
    // The scale of the moves: the mean distance from v to the worst
    // tetrahedron's other corners (the geometry's, whatever h says).
    double hv = 0;
    for (int s = 0; s < 4; ++s) {
      const int32_t w = m_.tet(worst)[s];
      if (w == v) continue;
      double d[3];
      sub(m_.point(w), x, d);
      hv += std::sqrt(dot(d, d)) / 3;
    }
    bool moved = false;
    // A move to p is kept when the star's smallest quality rises and every
    // tetrahedron stays positive (exact).
    auto try_move = [&](const double* p) {
      double mn, sum;
      if (!eval_star(Span(star_), p, old_min * (1 + 1e-6) + 1e-9, &mn, &sum, seq_) ||
          !exact_star_ok(v, Span(star_), p))
        return false;
      move(v, Span(star_), p, seq_);
      old_min = mn;
      moved = true;
      ++st_.sliver_moves;
      return true;
    };
    // Gradient of the worst quality by central differences.
    {
      const int32_t* tv = m_.tet(worst);
      double grad[3];
      const double eps = 1e-4 * hv;
      for (int k = 0; k < 3; ++k) {
        double pp[3] = {x[0], x[1], x[2]}, pm[3] = {x[0], x[1], x[2]};
        pp[k] += eps, pm[k] -= eps;
        const double* c1[4];
        const double* c2[4];
        for (int s = 0; s < 4; ++s) {
          c1[s] = tv[s] == v ? pp : m_.point(tv[s]);
          c2[s] = tv[s] == v ? pm : m_.point(tv[s]);
        }
        grad[k] = (tet_gamma(c1[0], c1[1], c1[2], c1[3]) - tet_gamma(c2[0], c2[1], c2[2], c2[3])) /
                  (2 * eps);
      }
      const double gn = std::sqrt(dot(grad, grad));
      if (gn > 0) {
        for (double step = 0.2 * hv; step > 0.005 * hv; step *= 0.5) {
          const double p[3] = {x[0] + step * grad[0] / gn, x[1] + step * grad[1] / gn,
                               x[2] + step * grad[2] / gn};
          if (try_move(p)) break;
        }
      }
    }
    // Random perturbations.
    for (int attempt = 0; attempt < 12; ++attempt) {
      const double mag = hv * (attempt < 6 ? 0.1 : 0.03);
      double d[3];
      for (double& c : d) c = 2 * uniform() - 1;
      const double* xv = m_.point(v);
      const double p[3] = {xv[0] + mag * d[0], xv[1] + mag * d[1], xv[2] + mag * d[2]};
      try_move(p);
    }
    return moved;
  }

  // ---------------------------------------------------------------- insertion

  // Grows cav (seeded with t) until every boundary face sees p (the
  // tetrahedron of the face and p positive); false if that needs crossing
  // a constrained face or more than kMaxCavity tetrahedra.
  bool grow_cavity(int32_t t, const double* p, std::vector<int32_t>& cav) {
    // Each tetrahedron's faces are checked once, when it joins: a face
    // found visible stays visible, and one hidden brings its neighbor in.
    cav.assign(1, t);
    for (size_t i = 0; i < cav.size(); ++i) {
      const int32_t c = cav[i];
      const int32_t* tv = m_.tet(c);
      for (int k = 0; k < 4; ++k) {
        const int32_t e = m_.neighbor(c, k);
        if (e >= 0 && std::find(cav.begin(), cav.end(), e >> 2) != cav.end()) continue;
        const double* q[4] = {m_.point(tv[0]), m_.point(tv[1]), m_.point(tv[2]), m_.point(tv[3])};
        q[k] = p;
        if (orient3d(q[0], q[1], q[2], q[3]) < 0) continue;  // visible
        if (m_.is_constrained(c, k) || int(cav.size()) >= kMaxCavity) return false;
        cav.push_back(e >> 2);
      }
    }
    return true;
  }

  // New tetrahedra of the star of p (vertex id pv) over the boundary of cav
  // and their smallest quality.
  double star_tets(const std::vector<int32_t>& cav, const double* p, int32_t pv,
                   std::vector<std::array<int32_t, 4>>& nt) {
    nt.clear();
    double mn = 1e300;
    for (int32_t c : cav)
      for (int k = 0; k < 4; ++k) {
        const int32_t e = m_.neighbor(c, k);
        if (e >= 0 && std::find(cav.begin(), cav.end(), e >> 2) != cav.end()) continue;
        const int32_t* tv = m_.tet(c);
        std::array<int32_t, 4> q = {tv[0], tv[1], tv[2], tv[3]};
        const double* x[4] = {m_.point(tv[0]), m_.point(tv[1]), m_.point(tv[2]), m_.point(tv[3])};
        x[k] = p;
        q[size_t(k)] = pv;
        mn = std::min(mn, tet_gamma(x[0], x[1], x[2], x[3]));
        nt.push_back(q);
      }
    return mn;
  }

  // Inserts a vertex near tetrahedron t (its centroid, off its constrained
  // faces, or off its largest face on either side) when the star of the
  // new vertex over a star-shaped cavity raises the smallest quality there.
  bool insert_near(int32_t t) {
    const int32_t* tv = m_.tet(t);
    const double* x[4] = {m_.point(tv[0]), m_.point(tv[1]), m_.point(tv[2]), m_.point(tv[3])};
    // Scale: the mean edge length of t (the geometry's, whatever h says);
    // the new vertex's size: the mean of its corners'.
    double ht = 0, hnew = 0, cen[3] = {0, 0, 0};
    for (int s = 0; s < 4; ++s) {
      hnew += 0.25 * h_[size_t(tv[s])];
      for (int k = 0; k < 3; ++k) cen[k] += 0.25 * x[s][k];
    }
    for (const auto& e : kTetEdges) {
      double d[3];
      sub(x[e[0]], x[e[1]], d);
      ht += std::sqrt(dot(d, d)) / 6;
    }
    // Candidates: the centroid, and for constrained faces points inward
    // from the face centroid (for two, from their common edge) at depths
    // 0.4, 0.6 and 0.8 h.
    std::vector<std::array<double, 3>> cand = {{cen[0], cen[1], cen[2]}};
    double dir[3] = {0, 0, 0}, base[3] = {0, 0, 0};
    int ncons = 0;
    const double depths[3] = {0.4, 0.6, 0.8};
    for (int k = 0; k < 4; ++k) {
      if (!m_.is_constrained(t, k)) continue;
      const int* f = kFaceOut[k];
      double u[3], w[3], n[3];
      sub(x[f[1]], x[f[0]], u), sub(x[f[2]], x[f[0]], w), cross(u, w, n);
      const double len = std::sqrt(dot(n, n));
      if (!(len > 0)) continue;
      // kFaceOut is counterclockwise seen from outside: n points out of t.
      double fc[3];
      for (int c = 0; c < 3; ++c) {
        fc[c] = (x[f[0]][c] + x[f[1]][c] + x[f[2]][c]) / 3;
        dir[c] -= n[c] / len;
        base[c] += fc[c];
      }
      ++ncons;
      for (double dep : depths)
        cand.push_back({fc[0] - dep * ht * n[0] / len, fc[1] - dep * ht * n[1] / len,
                        fc[2] - dep * ht * n[2] / len});
    }
    if (ncons >= 2) {
      const double len = std::sqrt(dot(dir, dir));
      if (len > 0)
        for (double dep : depths)
          cand.push_back({base[0] / ncons + dep * ht * dir[0] / len,
                          base[1] / ncons + dep * ht * dir[1] / len,
                          base[2] / ncons + dep * ht * dir[2] / len});
    }
    // The best candidate (smallest quality of its star), then a random
    // search around it with a shrinking radius.
    const int32_t pv = int32_t(m_.num_vertices());
    double best_q = -1e300;
    std::array<double, 3> best_p{};
    auto try_point = [&](const std::array<double, 3>& p) {
      if (!grow_cavity(t, p.data(), cav_)) return;
      const double nm = star_tets(cav_, p.data(), pv, nt_);
      if (nm > best_q) {
        best_q = nm;
        best_p = p;
      }
    };
    for (const auto& p : cand) try_point(p);
    // Points off t on both sides, along the normal of its largest face: a
    // flat tetrahedron (four nearly coplanar corners, as among the first
    // layer's points over a planar cap) has no good point in its plane,
    // and flips among coplanar points leave flat ones.
    {
      double n_best[3] = {0, 0, 0}, area2 = 0;
      for (int k = 0; k < 4; ++k) {
        const int* f = kFaceOut[k];
        double u[3], w[3], n[3];
        sub(x[f[1]], x[f[0]], u), sub(x[f[2]], x[f[0]], w), cross(u, w, n);
        if (dot(n, n) > area2) area2 = dot(n, n), std::copy(n, n + 3, n_best);
      }
      const double len = std::sqrt(area2);
      if (len > 0)
        for (double side : {1.0, -1.0})
          for (double dep : depths)
            try_point({cen[0] + side * dep * ht * n_best[0] / len,
                       cen[1] + side * dep * ht * n_best[1] / len,
                       cen[2] + side * dep * ht * n_best[2] / len});
    }
    if (best_q <= -1e300) return false;
    for (int it = 0; it < 24; ++it) {
      const double r = 0.25 * ht * (1 - it / 24.0);
      std::array<double, 3> p = best_p;
      for (double& c : p) c += r * (2 * uniform() - 1);
      try_point(p);
    }
    if (!grow_cavity(t, best_p.data(), cav_)) return false;
    double old_min = 1e300;
    for (int32_t c : cav_) old_min = std::min(old_min, cached(c));
    if (!(best_q > old_min + 1e-9)) return false;
    const std::vector<int32_t> best_cav = cav_;
    const double* cand_best = best_p.data();
    const int32_t v = m_.add_vertex(cand_best);
    h_.push_back(hnew);
    star_tets(best_cav, cand_best, v, nt_);
    fseq_.created.clear();
    if (commit(fseq_, best_cav.data(), int(best_cav.size()), nt_.data(), int(nt_.size())) !=
        Flip::kDone) {
      // Not expected (the cavity is star-shaped): the vertex stays unused.
      return false;
    }
    ++st_.insertions;
    smooth_vertex(v);
    climb_vertex(v);
    return true;
  }

  void sliver_phase() {
    // Work bound: tetrahedra treated, over all rounds, at most 4 times the
    // first round's count (plus a constant), whatever the rounds create.
    // The bad tetrahedra of a round after the first: those of the round
    // before and those it created or moved, still below the threshold
    // (no scan of the whole mesh).
    int64_t budget = -1;
    std::vector<int32_t> bad, log;
    for (int32_t t = 0; t < int32_t(m_.capacity()); ++t)
      if (m_.is_live(t) && cached(t) < opt_.sliver_threshold) bad.push_back(t);
    log_ = &log;
    for (int round = 0; round < opt_.sliver_rounds; ++round) {
      if (round > 0) {
        log.insert(log.end(), bad.begin(), bad.end());
        std::sort(log.begin(), log.end());
        log.erase(std::unique(log.begin(), log.end()), log.end());
        bad.clear();
        for (int32_t t : log)
          if (m_.is_live(t) && cached(t) < opt_.sliver_threshold) bad.push_back(t);
        log.clear();
      }
      if (bad.empty()) break;
      if (budget < 0) budget = 4 * int64_t(bad.size()) + 256;
      std::sort(bad.begin(), bad.end(), [&](int32_t a, int32_t b) {
        return cached(a) < cached(b) || (cached(a) == cached(b) && a < b);
      });
      bool changed = false, spent = false;
      for (int32_t t : bad) {
        if (!m_.is_live(t) || cached(t) >= opt_.sliver_threshold) continue;
        if (--budget < 0) {
          spent = true;
          break;
        }
        fseq_.created.clear();
        if (improve_topology(t, fseq_) == Flip::kDone) {
          changed = true;
          continue;
        }
        const int32_t tv[4] = {m_.tet(t)[0], m_.tet(t)[1], m_.tet(t)[2], m_.tet(t)[3]};
        for (int32_t v : tv) changed = climb_vertex(v) || changed;
        if (m_.is_live(t) && cached(t) < opt_.sliver_threshold && insert_near(t)) changed = true;
      }
      flip_pass(opt_.sliver_threshold, true);
      if (!changed || spent) break;
    }
    log_ = nullptr;
  }

  double uniform() {
    rng_ += 0x9e3779b97f4a7c15ull;
    uint64_t z = rng_;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return double(z >> 11) * 0x1p-53;
  }

 private:
  TetMesh& m_;
  std::vector<double> h_;  // per vertex (grows with inserted vertices)
  const OptimizeOptions& opt_;
  OptimizeStats& st_;
  uint64_t rng_;
  std::vector<double> q_;
  std::vector<uint8_t> dirty_;    // per slot: created or moved since the last flip pass
  std::vector<int32_t> touched_;  // the dirty slots (unless all_dirty_)
  bool all_dirty_ = true;
  std::vector<int32_t>* log_ = nullptr;  // sliver phase: created or moved tetrahedra
  FlipWork fseq_;                        // the sequential flips' worker
  std::vector<uint8_t> vpart_;           // parallel_flips(): the slab of each vertex
  std::vector<int32_t> work_, star_;
  StarScratch seq_;                            // the sequential smoothings' and climbs' scratch
  std::vector<int32_t> inc_off_, inc_, fill_;  // smoothing: vertex -> tetrahedra
  std::vector<int32_t> cav_;
  std::vector<std::array<int32_t, 4>> nt_;
};

}  // namespace

Status optimize_volume(TetMesh& mesh, const std::vector<double>& vertex_h,
                       const OptimizeOptions& options, OptimizeStats* stats,
                       const ProgressFn& progress) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  if (vertex_h.size() != mesh.num_vertices())
    return Status::Error("optimize: one size per vertex expected");
  for (double h : vertex_h)
    if (!(h > 0) || !std::isfinite(h))
      return Status::Error("optimize: sizes must be finite and > 0");
  OptimizeStats st;
  Optimizer opt(mesh, vertex_h, options, st);
  opt.compute_all_qualities();
  st.before = opt.stats();
  const int steps = 2 * options.passes + 1;
  int step = 0;
  for (int pass = 0; pass < options.passes; ++pass) {
    if (!report_progress(progress, double(step++) / steps, "optimize volume"))
      return Status::Cancelled();
    auto t = clock::now();
    opt.flip_pass(options.flip_threshold, false);
    st.flip_seconds += seconds_since(t);
    if (!report_progress(progress, double(step++) / steps, "optimize volume"))
      return Status::Cancelled();
    t = clock::now();
    opt.smooth_pass();
    st.smooth_seconds += seconds_since(t);
  }
  if (!report_progress(progress, double(step++) / steps, "optimize volume"))
    return Status::Cancelled();
  auto t = clock::now();
  opt.flip_pass(options.flip_threshold, false);
  st.flip_seconds += seconds_since(t);
  t = clock::now();
  opt.sliver_phase();
  st.sliver_seconds += seconds_since(t);
  st.after = opt.stats();
  st.seconds = seconds_since(t0);
  if (stats) *stats = st;
  return Status::Ok();
}

}  // namespace vm
