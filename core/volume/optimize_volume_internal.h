// What the passes of the volume optimizer (optimize_volume.h) share: the
// state of one optimize_volume() call (the mesh, the sizes, the cached
// qualities, what changed since the last flip pass), the workers' scratch
// and the passes' entry points. The files: optimize_volume.cpp (the driver,
// the quality cache, the slabs), optimize_volume_flips.cpp (the flip pass:
// 2-3 flips and edge removal), optimize_volume_smooth.cpp (vertex moves:
// the smoothing pass and the sliver phase's climb) and
// optimize_volume_slivers.cpp (the sliver phase, with vertex insertion near
// stubborn slivers). Not part of the API.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/quality/tet_quality.h"
#include "core/volume/edge_removal.h"
#include "core/volume/optimize_volume.h"
#include "core/volume/tet_mesh.h"
#include "core/volume/tet_topology.h"

namespace vm {
namespace optimize_volume_detail {

/// Largest ring of an edge removal (tetrahedra around the edge).
constexpr int kMaxRing = kMaxProgramRing;
/// Largest cavity of a vertex insertion near a sliver (tetrahedra).
constexpr int kMaxCavity = 24;
/// Slabs of a parallel smoothing or flip pass: fixed, so that the mesh does
/// not depend on the thread count.
constexpr size_t kParts = 8;

/// A read-only view of tetrahedron ids.
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

/// What a topological change did.
enum class Flip { kNone, kDone, kDeferred };

/// A flip worker: the sequential one (part -1: the mesh's own free list,
/// the optimizer's statistics and dirty list) or a slab's of a parallel
/// flip pass (its own slot pool, statistics and dirty list).
struct FlipWork {
  int part = -1;
  SlotPool pool;
  ReplaceScratch replace;
  std::vector<int32_t> ring_tets, ring, ids, created, work, later, touched;
  std::vector<RingTriangle> tris;
  int32_t old[64];
  OptimizeStats counts;
};

/// What gamma_t of a tetrahedron (p, x, y, z) of v's star needs besides
/// p, which does not change while v moves: x, y, z (positive with p in
/// v's place), n = (y - x) x (z - x), |n|, the longest squared edge of
/// the face (x, y, z) and the sum of h at x, y, z.
struct Opposite {
  double x[3], y[3], z[3], n[3], area2, len2, hsum;
};

/// A smoothing's scratch: one per part of a parallel smoothing pass.
struct StarScratch {
  std::vector<Opposite> opp;  // prepare_star()
  std::vector<double> q;      // qualities of the star at the point eval_star() tried
  int64_t moves = 0;          // smoothing moves
};

/// The state the passes share. Qualities are cached per tetrahedron slot
/// (2 for a free slot); a tetrahedron created or moved is dirty until the
/// next flip pass.
struct Optimizer {
  Optimizer(TetMesh& mesh, const std::vector<double>& sizes, const OptimizeOptions& opt,
            OptimizeStats& st)
      : m(mesh), h(sizes), options(opt), stats(st), rng(opt.seed) {}

  TetMesh& m;
  std::vector<double> h;  // per vertex (grows with inserted vertices)
  const OptimizeOptions& options;
  OptimizeStats& stats;
  uint64_t rng;
  std::vector<double> q;         // per slot: gamma_t
  std::vector<uint8_t> dirty;    // per slot: created or moved since the last flip pass
  std::vector<int32_t> touched;  // the dirty slots (unless all_dirty)
  bool all_dirty = true;
  std::vector<int32_t>* log = nullptr;  // sliver phase: created or moved tetrahedra
  FlipWork fseq;                        // the sequential flips' worker
  std::vector<uint8_t> vpart;           // parallel flips: the slab of each vertex
  std::vector<int32_t> work, star;
  StarScratch seq;                          // the sequential smoothings' and climbs' scratch
  std::vector<int32_t> inc_off, inc, fill;  // smoothing: vertex -> tetrahedra
  std::vector<int32_t> cav;
  std::vector<std::array<int32_t, 4>> nt;

  double quality(int32_t t) const {
    const int32_t* v = m.tet(t);
    return tet_gamma(m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3]));
  }
  double cached(int32_t t) const { return q[size_t(t)]; }

  /// Tetrahedron t was created or moved: dirty (listed once in touched),
  /// and logged when a log is on.
  void mark(int32_t t) {
    if (!dirty[size_t(t)]) dirty[size_t(t)] = 1, touched.push_back(t);
    if (log) log->push_back(t);
  }

  /// The next deterministic random number in [0, 1) (splitmix64).
  double uniform() {
    rng += 0x9e3779b97f4a7c15ull;
    uint64_t z = rng;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return double(z >> 11) * 0x1p-53;
  }
};

// ---- optimize_volume.cpp

/// The quality of every live tetrahedron, cached; everything dirty.
void compute_all_qualities(Optimizer& op);
/// Statistics of the cached qualities of the live tetrahedra (the formula
/// of tet_qualities(), clamped to [-1, 1] as there).
QualityStats cached_quality_stats(const Optimizer& op);
/// The slab (0 .. parts - 1) of each vertex: equal counts along the
/// longest axis of the vertices' box, ties to the same slab. halfway:
/// parts + 1 slabs, cut halfway between those cuts (at the count
/// fractions (2 j - 1) / (2 parts), j = 1 .. parts).
std::vector<uint8_t> vertex_slabs(const Optimizer& op, size_t parts, bool halfway = false);

// ---- optimize_volume_flips.cpp

/// Best topological change around tetrahedron t (2-3 on one of its faces
/// or removal of one of its edges) that raises the smallest quality of the
/// tetrahedra it replaces; applied if found (kDone). New ids into
/// w.created. A slab's worker reads only t, its neighbors and the
/// tetrahedra around its edges, and defers (kDeferred, nothing changed) a
/// change that would replace a tetrahedron with a vertex outside its slab.
Flip improve_topology(Optimizer& op, int32_t t, FlipWork& w);
/// Replaces the n_old tetrahedra old by the n_new tetrahedra nt (4 vertex
/// ids each): exact orientation of the new set, then (a slab's worker: if
/// the old tetrahedra are all in its slab, else kDeferred) the replacement
/// and the cache; new ids into w.created.
Flip commit(Optimizer& op, FlipWork& w, const int32_t* old, int n_old,
            const std::array<int32_t, 4>* nt, int n_new);
/// Flips on every tetrahedron below threshold (gamma_t) until none
/// improves; worst_first: in increasing quality, else in id order.
void flip_pass(Optimizer& op, double threshold, bool worst_first);

// ---- optimize_volume_smooth.cpp

/// Smart smoothing of free vertex v (its star found); whether it moved.
bool smooth_vertex(Optimizer& op, int32_t v);
/// One smoothing sweep over every free vertex (on the threads, by slabs).
void smooth_pass(Optimizer& op);
/// Raises the smallest quality of free vertex v's star (sliver phase);
/// whether it moved.
bool climb_vertex(Optimizer& op, int32_t v);

// ---- optimize_volume_slivers.cpp

/// The sliver phase: the tetrahedra below options.sliver_threshold, worst
/// first, by flips, vertex climbs and insertions near them, in rounds.
void sliver_phase(Optimizer& op);

}  // namespace optimize_volume_detail
}  // namespace vm
