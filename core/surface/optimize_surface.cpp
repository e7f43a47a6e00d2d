// Surface mesh optimization on the input surface (Marchandise et al. 2.1):
// phases per pass are edge swaps (maximizing the worse gamma_k of the pair,
// Lawson-like but by quality) and Laplacian smoothing projected back onto
// the input by a local closest-point walk.
#include "core/surface/optimize_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <numbers>

#include "core/geom/closest_point.h"
#include "core/geom/vec3.h"
#include "core/quality/triangle_quality.h"
#include "core/util/parallel.h"
#include "core/util/portable_math.h"

namespace vm {
namespace {

Vec3 normal(const double* a, const double* b, const double* c) {
  double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
         w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  Vec3 n{{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]}};
  double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (l > 0)
    for (double& v : n) v /= l;
  return n;
}

/// (b - a) x (c - a): the normal scaled by twice the area.
Vec3 area_normal(const double* a, const double* b, const double* c) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
               w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  return Vec3{{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]}};
}

/// The unit vector along the sum of `parts` (zero if the sum is zero).
Vec3 normal_sum(std::initializer_list<Vec3> parts) {
  Vec3 n{{0, 0, 0}};
  for (const Vec3& v : parts)
    for (int k = 0; k < 3; ++k) n[k] += v[k];
  const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (l > 0)
    for (double& v : n) v /= l;
  return n;
}

/// Below this gamma_k a triangle's normal is not trusted by the guards.
constexpr double kFlatGamma = 0.2;
/// A valence swap may lower the pair's worst gamma_k to this fraction.
constexpr double kValenceSwapMinGamma = 0.6;
/// A quality swap that makes valences less regular needs a triangle this poor.
constexpr double kPoorGamma = 0.5;
/// Smoothing may lower a star's worst gamma_k down to this when it raises
/// the star's mean.
constexpr double kSmoothingFloor = 0.8;
/// The smallest gain of the sum of a star's gamma_k worth a move.
constexpr double kMinGain = 1e-3;
/// A collapse may not create an edge longer than this times the size, and
/// may lower the worst gamma_k of the changed triangles down to kCollapseFloor.
constexpr double kMaxEdgeAfterCollapse = 1.4;
constexpr double kCollapseFloor = 0.4;
/// A split point may lie off its edge by at most this times the edge length.
constexpr double kMaxSplitOffset = 0.2;
/// The smoothing's blocks of consecutive vertex ids (also the fewest
/// vertices to smooth that it cuts into blocks), and vertices of one color
/// per chunk of its parallel loop.
constexpr size_t kSmoothBlock = 2048, kSmoothGrain = 512;

class Optimizer {
 public:
  enum class SwapGoal { kQuality, kValence };

  Optimizer(SurfaceMesh& m, std::vector<int32_t>& home, std::vector<uint8_t>& fixed,
            std::vector<double>& size, const SurfaceMesh& input, const TriangleAdjacency& input_adj,
            const SurfaceOptimizeOptions& o, const PinSlack* pins, std::vector<int32_t>* pin_of)
      : m_(m), home_(home), fixed_(fixed), size_(size), in_(input), in_adj_(input_adj) {
    collapse_ratio_ = o.collapse_ratio;
    if (pins) {
      pin_of_ = pin_of;
      input_h_ = pins->input_h;
      pin_slack_ = pin_of_ && input_h_ ? pins->slack : 0;
    }
    split_ratio_ = o.split_ratio;
    recent_.assign(m.num_vertices(), 1);
    q_.resize(m.num_triangles());
    parallel_for(q_.size(), 4096, [&](size_t begin, size_t end) {
      for (size_t t = begin; t < end; ++t) {
        const int32_t* T = &m.triangles[3 * t];
        q_[t] = gamma(T[0], T[1], T[2]);
      }
    });
    cos_turn_ = pm::cos(o.max_normal_turn_degrees * std::numbers::pi / 180);
    vt_.assign(m.num_vertices(), {});
    {
      std::vector<int32_t> count(m.num_vertices(), 0);
      for (int32_t v : m.triangles) ++count[size_t(v)];
      for (size_t v = 0; v < vt_.size(); ++v) vt_[v].reserve(size_t(count[v]));
    }
    for (size_t t = 0; t < m.num_triangles(); ++t)
      for (int c = 0; c < 3; ++c) vt_[size_t(m.triangles[3 * t + c])].push_back(int32_t(t));
    opp_.resize(m.triangles.size());
    parallel_for(m.num_triangles(), 4096, [&](size_t begin, size_t end) {
      for (size_t t = begin; t < end; ++t) refresh_triangle(int32_t(t));
    });
  }

  /// Starts the next pass: work is limited to what changed since the
  /// previous pass started.
  void next_pass() { ++pass_; }

  /// The first pass works only on the flagged vertices (one per vertex).
  void start_from(const std::vector<uint8_t>& flags) {
    for (size_t v = 0; v < recent_.size(); ++v) recent_[v] = flags[v] ? pass_ : pass_ - 2;
  }

  /// Nothing changes beyond `rings` rings of the vertices flagged in
  /// `flags` (one per vertex).
  void restrict_to(const std::vector<uint8_t>& flags, int rings) {
    region_ = flags;
    for (int ring = 0; ring < rings; ++ring) {
      std::vector<uint8_t> grown = region_;
      for (size_t t = 0; t < m_.num_triangles(); ++t) {
        const int32_t* T = tri(int32_t(t));
        if (T[0] >= 0 && (region_[size_t(T[0])] || region_[size_t(T[1])] || region_[size_t(T[2])]))
          for (int c = 0; c < 3; ++c) grown[size_t(T[c])] = 1;
      }
      region_.swap(grown);
    }
  }

  /// Splits the interior edges longer than split_ratio times the target
  /// size at their midpoint projected onto the input (see try_split).
  size_t split_pass() {
    size_t splits = 0;
    if (size_.empty() || !(split_ratio_ > 0)) return 0;
    const int32_t count = int32_t(m_.num_triangles());
    for (int32_t t = 0; t < count; ++t)
      for (int k = 0; k < 3 && tri(t)[0] >= 0 && active(t); ++k) {
        const int32_t a = tri(t)[k], b = tri(t)[(k + 1) % 3];
        const double l2 = dist2(p(a), p(b));
        const double limit = split_ratio_ * 0.5 * (size_[size_t(a)] + size_[size_t(b)]);
        if (l2 > limit * limit && try_split(t, k)) ++splits;
      }
    return splits;
  }

  /// Collapses the interior edges shorter than collapse_ratio times the
  /// target size (see try_collapse). Needs sizes.
  size_t collapse_pass() {
    size_t collapses = 0;
    if (size_.empty()) return 0;
    for (int32_t t = 0; t < int32_t(m_.num_triangles()); ++t)
      for (int k = 0; k < 3 && tri(t)[0] >= 0 && active(t); ++k) {
        const int32_t a = tri(t)[k], b = tri(t)[(k + 1) % 3];
        const double* pa = p(a);
        const double* pb = p(b);
        const double len =
            std::sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) +
                      (pa[2] - pb[2]) * (pa[2] - pb[2]));
        if (len < collapse_ratio_ * std::min(size_[size_t(a)], size_[size_t(b)]) &&
            try_collapse(a, b))
          ++collapses;
      }
    return collapses;
  }

  /// Removes the collapsed vertices and triangles: renumbers mesh, home,
  /// fixed and size. Returns the new number of each old vertex (-1: gone).
  std::vector<int32_t> compact(std::vector<uint8_t>& fixed, std::vector<double>& size) {
    std::vector<int32_t> renumber(m_.num_vertices(), -1);
    int32_t n = 0;
    for (size_t v = 0; v < renumber.size(); ++v) {
      if (!dead_.empty() && dead_[v]) continue;
      renumber[v] = n;
      for (int k = 0; k < 3; ++k) m_.points[3 * size_t(n) + k] = m_.points[3 * v + k];
      home_[size_t(n)] = home_[v];
      fixed[size_t(n)] = fixed[v];
      if (!size.empty()) size[size_t(n)] = size[v];
      if (pin_of_) (*pin_of_)[size_t(n)] = (*pin_of_)[v];
      ++n;
    }
    m_.points.resize(3 * size_t(n));
    home_.resize(size_t(n));
    fixed.resize(size_t(n));
    if (!size.empty()) size.resize(size_t(n));
    if (pin_of_) pin_of_->resize(size_t(n));
    size_t kept = 0;
    for (size_t t = 0; t < m_.num_triangles(); ++t) {
      if (m_.triangles[3 * t] < 0) continue;
      for (int c = 0; c < 3; ++c)
        m_.triangles[3 * kept + size_t(c)] = renumber[size_t(m_.triangles[3 * t + size_t(c)])];
      ++kept;
    }
    m_.triangles.resize(3 * kept);
    return renumber;
  }

  /// One pass of edge swaps toward `goal`, at most one a triangle: kQuality
  /// swaps that improve the worse triangle; kValence swaps that bring the
  /// valences of their four vertices closer to the regular ones (6 inside, 4
  /// on an opening), when neither new triangle is poor (the smoothing that
  /// follows restores the shapes). With few triangles to try, in order;
  /// else first, on the threads, each block's triangles whose vertices all
  /// have their star in the block (plan_swaps()), in order, then the others
  /// in order. A swap changes only triangles of its vertices' stars, so
  /// swaps of different blocks at the same time touch different triangles,
  /// and the mesh is the same on any thread count.
  size_t swap_pass(SwapGoal goal) {
    auto try_triangle = [&](int32_t t) {
      for (int k = 0; k < 3 && active(t); ++k)
        if (try_swap(t, k, goal)) return size_t(1);
      return size_t(0);
    };
    const size_t nt = m_.num_triangles();
    size_t waiting = 0;
    for (size_t t = 0; t < nt && waiting < kSmoothBlock; ++t) waiting += active(int32_t(t));
    if (waiting < kSmoothBlock) {
      size_t swaps = 0;
      for (size_t t = 0; t < nt; ++t) swaps += try_triangle(int32_t(t));
      return swaps;
    }
    plan_swaps();
    const size_t blocks = tri_block_start_.size() - 1;
    size_t swaps = parallel_sum<size_t>(blocks, 1, [&](size_t begin, size_t end) {
      size_t n = 0;
      for (size_t b = begin; b < end; ++b)
        for (int32_t i = tri_block_start_[b]; i < tri_block_start_[b + 1]; ++i)
          n += try_triangle(inner_tris_[size_t(i)]);
      return n;
    });
    for (int32_t t : border_tris_) swaps += try_triangle(t);
    return swaps;
  }

  /// One pass of smoothing (try_move) over the movable vertices changed in
  /// this pass or the previous one. With few of them at the start, in id
  /// order; else the vertices are cut into blocks of consecutive ids
  /// (plan_smoothing()): first each block's inner vertices, in order, the
  /// blocks on the threads; then the others color by color. Moves that run
  /// at the same time have stars with no triangle in common and neither
  /// holds the other, so the mesh is the same on any thread count.
  size_t smooth_pass() {
    size_t waiting = 0;
    for (size_t v = 0; v < m_.num_vertices(); ++v) waiting += movable(v) && recent_[v] + 1 >= pass_;
    if (waiting < kSmoothBlock) {
      size_t moves = 0;
      for (size_t v = 0; v < m_.num_vertices(); ++v)
        if (movable(v) && recent_[v] + 1 >= pass_ && try_move(int32_t(v))) ++moves;
      return moves;
    }
    plan_smoothing();
    auto move_all = [&](const int32_t* vs, size_t n) {
      size_t m = 0;
      for (size_t i = 0; i < n; ++i)
        if (recent_[size_t(vs[i])] + 1 >= pass_ && try_move(vs[i])) ++m;
      return m;
    };
    const size_t blocks = block_start_.size() - 1;
    size_t moves = parallel_sum<size_t>(blocks, 1, [&](size_t begin, size_t end) {
      size_t m = 0;
      for (size_t b = begin; b < end; ++b)
        m += move_all(inner_.data() + block_start_[b],
                      size_t(block_start_[b + 1] - block_start_[b]));
      return m;
    });
    for (size_t c = 0; c + 1 < color_start_.size(); ++c) {
      const int32_t* group = by_color_.data() + color_start_[c];
      moves += parallel_sum<size_t>(
          size_t(color_start_[c + 1] - color_start_[c]), kSmoothGrain,
          [&](size_t begin, size_t end) { return move_all(group + begin, end - begin); });
    }
    return moves;
  }

 private:
  bool in_region(int32_t v) const { return region_.empty() || region_[size_t(v)]; }
  bool movable(size_t v) const {
    return (!fixed_[v] || (fixed_[v] == kPinned && pin_slack_ > 0)) &&
           (region_.empty() || region_[v]);
  }
  const double* p(int32_t v) const { return &m_.points[3 * size_t(v)]; }
  int32_t* tri(int32_t t) { return &m_.triangles[3 * size_t(t)]; }
  double gamma(int32_t a, int32_t b, int32_t c) const { return triangle_gamma(p(a), p(b), p(c)); }

  /// The other triangle with edge (b, a) of t's edge k = (a, b), or -1:
  /// across() kept per edge in opp_ (swap_pass tries every edge).
  int32_t across_edge(int32_t t, int k) const { return opp_[3 * size_t(t) + size_t(k)]; }

  void refresh_triangle(int32_t t) {
    const int32_t* T = tri(t);
    for (int k = 0; k < 3; ++k)
      opp_[3 * size_t(t) + size_t(k)] = T[0] < 0 ? -1 : across(t, T[k], T[(k + 1) % 3]);
  }

  /// After a change of triangles: `changed` (their new corners, or
  /// collapsed) had the directed edges `edges` before or after it. An
  /// edge's cached neighbor can change only when a triangle gains or
  /// loses its reverse: those of the changed triangles and of the
  /// triangles holding the reverse of one of `edges` are recomputed.
  void refresh_after(const std::vector<int32_t>& changed,
                     const std::vector<std::array<int32_t, 2>>& edges) {
    if (opp_.size() < m_.triangles.size()) opp_.resize(m_.triangles.size());
    for (int32_t t : changed) refresh_triangle(t);
    for (const auto& e : edges) {
      // Triangles with the directed edge (e[1], e[0]).
      for (int32_t u : vt_[size_t(e[1])]) {
        const int32_t* U = tri(u);
        for (int c = 0; c < 3; ++c)
          if (U[c] == e[1] && U[(c + 1) % 3] == e[0])
            opp_[3 * size_t(u) + size_t(c)] = across(u, e[1], e[0]);
      }
    }
  }

  /// refresh_after()'s scratch, per thread (swaps run on the threads).
  static std::vector<std::array<int32_t, 2>>& edges_scratch() {
    thread_local std::vector<std::array<int32_t, 2>> edges;
    return edges;
  }

  /// Appends the directed edges of each of `tris` (live ones) to
  /// edges_scratch().
  void note_edges(std::initializer_list<int32_t> tris) {
    for (int32_t t : tris) note_edges_of(t);
  }
  void note_edges_of(int32_t t) {
    const int32_t* T = tri(t);
    if (T[0] < 0) return;
    for (int k = 0; k < 3; ++k) edges_scratch().push_back({T[k], T[(k + 1) % 3]});
  }

  /// The other triangle with edge (b, a), or -1.
  int32_t across(int32_t t, int32_t a, int32_t b) const {
    int32_t found = -1;
    for (int32_t u : vt_[size_t(a)]) {
      if (u == t) continue;
      const int32_t* U = &m_.triangles[3 * size_t(u)];
      for (int c = 0; c < 3; ++c)
        if (U[c] == b && U[(c + 1) % 3] == a) {
          if (found >= 0) return -1;  // non-manifold: leave it alone
          found = u;
        }
    }
    return found;
  }

  bool has_edge(int32_t a, int32_t b) const {
    for (int32_t u : vt_[size_t(a)]) {
      const int32_t* U = &m_.triangles[3 * size_t(u)];
      if (U[0] == b || U[1] == b || U[2] == b) return true;
    }
    return false;
  }

  static void erase(std::vector<int32_t>& list, int32_t x) {
    list.erase(std::find(list.begin(), list.end(), x));
  }

  /// An edge between two vertices on openings or creases may be a crease
  /// (or an opening edge): it stays.
  bool on_crease(int32_t a, int32_t b) const {
    auto kept = [&](int32_t v) {
      return fixed_[size_t(v)] == kOnOpening || fixed_[size_t(v)] == kOnFeature;
    };
    return kept(a) && kept(b);
  }

  int valence_excess(int32_t v, int change) const {
    // Neighbors: one per star triangle, plus one on an opening.
    const bool opening = fixed_[size_t(v)] == kOnOpening;
    const int valence = int(vt_[size_t(v)].size()) + (opening ? 1 : 0) + change;
    return std::abs(valence - (opening ? 4 : 6));
  }

  // t = (a, b, c), u = (b, a, d) -> t = (a, d, c), u = (d, b, c).
  bool try_swap(int32_t t, int k, SwapGoal goal) {
    int32_t* T = tri(t);
    if (T[0] < 0) return false;  // collapsed
    const int32_t a = T[k], b = T[(k + 1) % 3], c = T[(k + 2) % 3];
    const int32_t u = across_edge(t, k);
    if (u < 0) return false;
    int32_t* U = tri(u);
    int32_t d = -1;
    for (int j = 0; j < 3; ++j)
      if (U[j] != a && U[j] != b) d = U[j];
    if (d < 0 || d == c || on_crease(a, b) || !in_region(d)) return false;
    const int excess_before =
        valence_excess(a, 0) + valence_excess(b, 0) + valence_excess(c, 0) + valence_excess(d, 0);
    const int excess_after =
        valence_excess(a, -1) + valence_excess(b, -1) + valence_excess(c, 1) + valence_excess(d, 1);
    const double before = std::min(q_[size_t(t)], q_[size_t(u)]);
    // Undoing a valence swap needs a poor triangle.
    if (goal == SwapGoal::kValence ? excess_after >= excess_before
                                   : excess_after > excess_before && before > kPoorGamma)
      return false;
    const double g1 = gamma(a, d, c), g2 = gamma(d, b, c);
    const double after = std::min(g1, g2);
    if (goal == SwapGoal::kQuality ? !(after > before + 1e-9)
                                   : after < kValenceSwapMinGamma * before)
      return false;
    if (has_edge(c, d)) return false;
    // The normal guard; a nearly flat triangle's normal means nothing, so
    // next to one the pair's area-weighted normal stands for both.
    Vec3 nt = normal(p(a), p(b), p(c)), nu = normal(p(b), p(a), p(d));
    const Vec3 n1 = normal(p(a), p(d), p(c)), n2 = normal(p(d), p(b), p(c));
    if (q_[size_t(t)] < kFlatGamma || q_[size_t(u)] < kFlatGamma)
      nt = nu = normal_sum({area_normal(p(a), p(b), p(c)), area_normal(p(b), p(a), p(d))});
    if (dot(nt, nu) < cos_turn_ || dot(n1, n2) < cos_turn_) return false;
    for (const Vec3& n : {n1, n2})
      if (dot(n, nt) < cos_turn_ || dot(n, nu) < cos_turn_) return false;
    edges_scratch().clear();
    note_edges({t, u});
    T[0] = a, T[1] = d, T[2] = c;
    U[0] = d, U[1] = b, U[2] = c;
    erase(vt_[size_t(a)], u);
    erase(vt_[size_t(b)], t);
    vt_[size_t(c)].push_back(u);
    vt_[size_t(d)].push_back(t);
    note_edges({t, u});
    refresh_after({t, u}, edges_scratch());
    q_[size_t(t)] = g1;
    q_[size_t(u)] = g2;
    for (int32_t v : {a, b, c, d}) recent_[size_t(v)] = pass_;
    return true;
  }

  /// A triangle with a vertex changed in this pass or the previous one.
  bool active(int32_t t) const {
    const int32_t* T = &m_.triangles[3 * size_t(t)];
    return T[0] >= 0 &&
           (recent_[size_t(T[0])] + 1 >= pass_ || recent_[size_t(T[1])] + 1 >= pass_ ||
            recent_[size_t(T[2])] + 1 >= pass_) &&
           (region_.empty() ||
            (region_[size_t(T[0])] && region_[size_t(T[1])] && region_[size_t(T[2])]));
  }

  /// Records that v and the vertices of its star changed. Two moves of a
  /// color may mark a common neighbor (with the same value): an atomic
  /// store (the compiler's builtin: Emscripten 3.1.6's library has no
  /// std::atomic_ref).
  void mark_star(int32_t v) {
    for (int32_t t : vt_[size_t(v)])
      for (int c = 0; c < 3; ++c)
        __atomic_store_n(&recent_[size_t(m_.triangles[3 * size_t(t) + size_t(c)])], pass_,
                         __ATOMIC_RELAXED);
  }

  /// Per vertex: whether its star lies in its block of kSmoothBlock
  /// consecutive ids (into block_inner_).
  void find_block_inner() {
    const size_t n = m_.num_vertices();
    block_inner_.assign(n, 0);
    parallel_for(n, kSmoothBlock, [&](size_t first, size_t last) {
      for (size_t v = first; v < last; ++v) {
        bool inner = !vt_[v].empty();
        for (int32_t t : vt_[v])
          for (int k = 0; k < 3; ++k) {
            const size_t w = size_t(m_.triangles[3 * size_t(t) + size_t(k)]);
            inner = inner && w >= first && w < last;
          }
        block_inner_[v] = inner;
      }
    });
  }

  /// The swap pass's order: per block (of its first vertex), the live
  /// triangles whose three vertices are inner in it (inner_tris_, offsets
  /// in tri_block_start_); the others (border_tris_). Both ascending.
  void plan_swaps() {
    find_block_inner();
    const size_t blocks = (m_.num_vertices() + kSmoothBlock - 1) / kSmoothBlock;
    std::vector<int32_t> count(blocks + 1, 0);
    border_tris_.clear();
    auto inner_block = [&](size_t t) -> int64_t {
      const int32_t* T = &m_.triangles[3 * t];
      if (T[0] < 0 || !block_inner_[size_t(T[0])] || !block_inner_[size_t(T[1])] ||
          !block_inner_[size_t(T[2])])
        return -1;
      return int64_t(size_t(T[0]) / kSmoothBlock);
    };
    for (size_t t = 0; t < m_.num_triangles(); ++t) {
      const int64_t b = inner_block(t);
      if (b >= 0) ++count[size_t(b) + 1];
    }
    for (size_t b = 0; b < blocks; ++b) count[b + 1] += count[b];
    tri_block_start_ = count;
    inner_tris_.resize(size_t(count.back()));
    for (size_t t = 0; t < m_.num_triangles(); ++t) {
      const int64_t b = inner_block(t);
      if (b >= 0) {
        inner_tris_[size_t(count[size_t(b)]++)] = int32_t(t);
      } else if (m_.triangles[3 * t] >= 0) {
        border_tris_.push_back(int32_t(t));
      }
    }
  }

  /// The smoothing's order: the movable vertices whose star lies in their
  /// block of kSmoothBlock consecutive ids (inner_, by block, offsets in
  /// block_start_), and the others colored greedily in id order, each with
  /// the smallest color none of its such neighbors of lower id has
  /// (by_color_, by color, offsets in color_start_).
  void plan_smoothing() {
    find_block_inner();
    const size_t n = m_.num_vertices();
    const size_t blocks = (n + kSmoothBlock - 1) / kSmoothBlock;
    color_.assign(n, -1);
    inner_.clear();
    block_start_.assign(1, 0);
    std::vector<uint8_t> used;
    int colors = 0;
    for (size_t b = 0; b < blocks; ++b) {
      const size_t first = b * kSmoothBlock, last = std::min(n, first + kSmoothBlock);
      for (size_t v = first; v < last; ++v) {
        if (!movable(v) || vt_[v].empty()) continue;
        if (block_inner_[v]) {
          inner_.push_back(int32_t(v));
          continue;
        }
        // The colors around v (at most 3 per star triangle, so one of the
        // first 3 |star| + 1 is free).
        used.assign(3 * vt_[v].size() + 1, 0);
        for (int32_t t : vt_[v])
          for (int k = 0; k < 3; ++k) {
            const int32_t c = color_[size_t(m_.triangles[3 * size_t(t) + size_t(k)])];
            if (c >= 0 && size_t(c) < used.size()) used[size_t(c)] = 1;
          }
        const int c = int(std::find(used.begin(), used.end(), 0) - used.begin());
        color_[v] = c;
        colors = std::max(colors, c + 1);
      }
      block_start_.push_back(int32_t(inner_.size()));
    }
    color_start_.assign(size_t(colors) + 1, 0);
    for (int32_t c : color_)
      if (c >= 0) ++color_start_[size_t(c) + 1];
    for (size_t c = 0; c < size_t(colors); ++c) color_start_[c + 1] += color_start_[c];
    by_color_.resize(size_t(color_start_.back()));
    std::vector<int32_t> next(color_start_.begin(), color_start_.end() - 1);
    for (size_t v = 0; v < n; ++v)
      if (color_[v] >= 0) by_color_[size_t(next[size_t(color_[v])]++)] = int32_t(v);
  }

  static double dist2(const double* x, const double* y) {
    return (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
           (x[2] - y[2]) * (x[2] - y[2]);
  }

  /// Splits the edge (a, b) = corners k, k + 1 of t, shared with u = (b, a,
  /// d), at its midpoint projected onto the input: t = (a, b, c) becomes
  /// (a, n, c) + (n, b, c), u becomes (b, n, d) + (n, a, d). Refused on an
  /// opening edge and where a new triangle would turn by more than the guard.
  bool try_split(int32_t t, int k) {
    int32_t* T = tri(t);
    const int32_t a = T[k], b = T[(k + 1) % 3], c = T[(k + 2) % 3];
    const int32_t u = across_edge(t, k);
    if (u < 0 || on_crease(a, b)) return false;
    int32_t d = -1;
    for (int j = 0; j < 3; ++j)
      if (tri(u)[j] != a && tri(u)[j] != b) d = tri(u)[j];
    if (!in_region(d)) return false;
    const double mid[3] = {0.5 * (p(a)[0] + p(b)[0]), 0.5 * (p(a)[1] + p(b)[1]),
                           0.5 * (p(a)[2] + p(b)[2])};
    double x[3];
    const int32_t home = project_near(mid, home_[size_t(a)], in_, in_adj_, x);
    // Far from the edge (a crease between a and b): leave it.
    if (dist2(mid, x) > kMaxSplitOffset * kMaxSplitOffset * dist2(p(a), p(b))) return false;
    Vec3 nt = normal(p(a), p(b), p(c)), nu = normal(p(b), p(a), p(d));
    if (q_[size_t(t)] < kFlatGamma || q_[size_t(u)] < kFlatGamma)
      nt = nu = normal_sum({area_normal(p(a), p(b), p(c)), area_normal(p(b), p(a), p(d))});
    if (dot(normal(p(a), x, p(c)), nt) < cos_turn_ || dot(normal(x, p(b), p(c)), nt) < cos_turn_ ||
        dot(normal(p(b), x, p(d)), nu) < cos_turn_ || dot(normal(x, p(a), p(d)), nu) < cos_turn_)
      return false;
    const int32_t n = int32_t(home_.size());
    m_.points.insert(m_.points.end(), x, x + 3);
    home_.push_back(home);
    fixed_.push_back(kFree);
    if (pin_of_) pin_of_->push_back(-1);
    size_.push_back(0.5 * (size_[size_t(a)] + size_[size_t(b)]));
    vt_.emplace_back();
    recent_.push_back(pass_);
    if (!region_.empty()) region_.push_back(1);
    if (!dead_.empty()) dead_.push_back(0);
    const int32_t t2 = int32_t(m_.num_triangles()), u2 = t2 + 1;
    edges_scratch().clear();
    note_edges({t, u});
    T[0] = a, T[1] = n, T[2] = c;
    int32_t* U = tri(u);
    U[0] = b, U[1] = n, U[2] = d;
    m_.triangles.insert(m_.triangles.end(), {n, b, c, n, a, d});
    erase(vt_[size_t(b)], t);
    erase(vt_[size_t(a)], u);
    vt_[size_t(b)].push_back(t2);
    vt_[size_t(c)].push_back(t2);
    vt_[size_t(a)].push_back(u2);
    vt_[size_t(d)].push_back(u2);
    vt_[size_t(n)] = {t, u, t2, u2};
    note_edges({t, u, t2, u2});
    refresh_after({t, u, t2, u2}, edges_scratch());
    for (int32_t w : {t, u, t2, u2}) {
      const int32_t* W = tri(w);
      if (size_t(w) >= q_.size()) q_.resize(size_t(w) + 1);
      q_[size_t(w)] = gamma(W[0], W[1], W[2]);
    }
    for (int32_t v : {a, b, c, d, n}) recent_[size_t(v)] = pass_;
    return true;
  }

  /// The vertices sharing an edge with v.
  void neighbors(int32_t v, std::vector<int32_t>& out) const {
    out.clear();
    for (int32_t t : vt_[size_t(v)])
      for (int c = 0; c < 3; ++c) {
        const int32_t w = m_.triangles[3 * size_t(t) + size_t(c)];
        if (w != v && std::find(out.begin(), out.end(), w) == out.end()) out.push_back(w);
      }
  }

  /// Collapses edge (a, b): into the vertex on an opening if one is (both:
  /// refused), else into the midpoint projected onto the input. Refused
  /// unless the link condition holds (the only common neighbors are the
  /// apexes of the edge's two triangles, so the mesh stays manifold), no
  /// triangle turns by more than the normal guard, no edge grows beyond
  /// kMaxEdgeAfterCollapse times the size, and the worst gamma_k of the
  /// changed triangles ends at least at min(its value before, kCollapseFloor).
  bool try_collapse(int32_t a, int32_t b) {
    if (fixed_[size_t(a)] && fixed_[size_t(b)]) return false;
    if (fixed_[size_t(a)]) std::swap(a, b);  // a goes, b stays
    neighbors(a, na_);
    neighbors(b, nb_);
    int common = 0;
    for (int32_t w : na_)
      if (std::find(nb_.begin(), nb_.end(), w) != nb_.end()) ++common;
    int shared = 0;  // triangles with edge (a, b)
    for (int32_t t : vt_[size_t(a)]) {
      const int32_t* T = tri(t);
      if (T[0] == b || T[1] == b || T[2] == b) ++shared;
    }
    if (shared != 2 || common != 2) return false;
    // Every triangle it changes, in the region.
    if (!region_.empty() &&
        (std::any_of(na_.begin(), na_.end(), [&](int32_t w) { return !in_region(w); }) ||
         std::any_of(nb_.begin(), nb_.end(), [&](int32_t w) { return !in_region(w); })))
      return false;
    double target[3];
    int32_t target_home = home_[size_t(b)];
    if (fixed_[size_t(b)]) {
      std::copy(p(b), p(b) + 3, target);
    } else {
      const double mid[3] = {0.5 * (p(a)[0] + p(b)[0]), 0.5 * (p(a)[1] + p(b)[1]),
                             0.5 * (p(a)[2] + p(b)[2])};
      target_home = project_near(mid, home_[size_t(a)], in_, in_adj_, target);
    }
    // The changed triangles: every triangle of a or b but the two removed.
    changed_.clear();
    double before = 1;
    for (int32_t v : {a, b})
      for (int32_t t : vt_[size_t(v)]) {
        const int32_t* T = tri(t);
        before = std::min(before, gamma(T[0], T[1], T[2]));
        const bool on_edge =
            (T[0] == a || T[1] == a || T[2] == a) && (T[0] == b || T[1] == b || T[2] == b);
        if (!on_edge && std::find(changed_.begin(), changed_.end(), t) == changed_.end())
          changed_.push_back(t);
      }
    const double limit = kMaxEdgeAfterCollapse * size_[size_t(b)];
    double after = 1;
    for (int32_t t : changed_) {
      const int32_t* T = tri(t);
      const double* q[3];
      for (int c = 0; c < 3; ++c) q[c] = T[c] == a || T[c] == b ? target : p(T[c]);
      const Vec3 n_old = normal(p(T[0]), p(T[1]), p(T[2])), n_new = normal(q[0], q[1], q[2]);
      if (dot(n_old, n_new) < cos_turn_) return false;
      for (int c = 0; c < 3; ++c) {
        const double* x = q[c];
        const double* y = q[(c + 1) % 3];
        const double l2 = (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
                          (x[2] - y[2]) * (x[2] - y[2]);
        if (l2 > limit * limit) return false;
      }
      after = std::min(after, triangle_gamma(q[0], q[1], q[2]));
    }
    if (after < std::min(before, kCollapseFloor)) return false;
    // Apply: drop the two triangles on the edge, hand a's others to b.
    std::vector<int32_t> star_a = vt_[size_t(a)];
    edges_scratch().clear();
    for (int32_t t : star_a) note_edges_of(t);
    for (int32_t t : star_a) {
      int32_t* T = tri(t);
      const bool on_edge = T[0] == b || T[1] == b || T[2] == b;
      if (on_edge) {
        for (int c = 0; c < 3; ++c)
          if (T[c] != a) erase(vt_[size_t(T[c])], t);
        T[0] = T[1] = T[2] = -1;
      } else {
        for (int c = 0; c < 3; ++c)
          if (T[c] == a) T[c] = b;
        vt_[size_t(b)].push_back(t);
      }
    }
    vt_[size_t(a)].clear();
    if (dead_.empty()) dead_.assign(m_.num_vertices(), 0);
    dead_[size_t(a)] = 1;
    std::copy(target, target + 3, &m_.points[3 * size_t(b)]);
    home_[size_t(b)] = target_home;
    for (int32_t t : changed_) {
      const int32_t* T = tri(t);
      q_[size_t(t)] = gamma(T[0], T[1], T[2]);
    }
    for (int32_t t : star_a) note_edges_of(t);
    refresh_after(star_a, edges_scratch());
    mark_star(b);
    return true;
  }

  bool try_move(int32_t v) {
    const auto& star = vt_[size_t(v)];
    if (star.empty()) return false;
    // Target: the mean of the apexes that would make each star triangle
    // equilateral on its opposite edge, in its own plane.
    double target[3] = {0, 0, 0};
    double before = 1, before_sum = 0;
    for (int32_t t : star) {
      const int32_t* T = tri(t);
      const double g = q_[size_t(t)];
      before = std::min(before, g);
      before_sum += g;
      int c = 0;
      while (T[c] != v) ++c;
      const double *b = p(T[(c + 1) % 3]), *e = p(T[(c + 2) % 3]);
      const Vec3 n = normal(p(v), b, e);
      const double d[3] = {e[0] - b[0], e[1] - b[1], e[2] - b[2]};
      const double side[3] = {n[1] * d[2] - n[2] * d[1], n[2] * d[0] - n[0] * d[2],
                              n[0] * d[1] - n[1] * d[0]};  // |side| = |d|, into the triangle
      for (int k = 0; k < 3; ++k) target[k] += 0.5 * (b[k] + e[k]) + 0.8660254037844386 * side[k];
    }
    for (double& x : target) x /= double(star.size());
    double projected[3];
    int32_t new_home = project_near(target, home_[size_t(v)], in_, in_adj_, projected);
    if (fixed_[size_t(v)] == kPinned) {
      // Within the slack of its input vertex: the target pulled towards it
      // (short of the limit, which projecting a chord may overshoot).
      const int32_t w = (*pin_of_)[size_t(v)];
      const double* anchor = &in_.points[3 * size_t(w)];
      const double r = pin_slack_ * (*input_h_)[size_t(w)];
      const double d = std::sqrt(dist2(anchor, projected));
      if (d > r) {
        const double s = 0.8 * r / d;
        for (int k = 0; k < 3; ++k) target[k] = anchor[k] + (projected[k] - anchor[k]) * s;
        new_home = project_near(target, home_[size_t(v)], in_, in_adj_, projected);
        if (dist2(anchor, projected) > r * r) return false;
      }
    }
    double* pv = &m_.points[3 * size_t(v)];
    const double old[3] = {pv[0], pv[1], pv[2]};
    // The guard's reference normals: each triangle's own, or the star's
    // area-weighted normal for a nearly flat one.
    // Scratch per thread (a color's moves run at the same time).
    thread_local std::vector<Vec3> old_normals;
    thread_local std::vector<double> new_q;
    old_normals.clear();
    Vec3 star_normal{{0, 0, 0}};
    for (int32_t t : star) {
      const int32_t* T = tri(t);
      old_normals.push_back(normal(p(T[0]), p(T[1]), p(T[2])));
      const Vec3 an = area_normal(p(T[0]), p(T[1]), p(T[2]));
      for (int k = 0; k < 3; ++k) star_normal[k] += an[k];
    }
    star_normal = normal_sum({star_normal});
    for (size_t i = 0; i < star.size(); ++i)
      if (q_[size_t(star[i])] < kFlatGamma) old_normals[i] = star_normal;
    std::copy(projected, projected + 3, pv);
    double after = 1, after_sum = 0;
    bool ok = true;
    new_q.clear();
    for (size_t i = 0; i < star.size() && ok; ++i) {
      const int32_t* T = tri(star[i]);
      const double g = gamma(T[0], T[1], T[2]);
      new_q.push_back(g);
      after = std::min(after, g);
      after_sum += g;
      ok = dot(normal(p(T[0]), p(T[1]), p(T[2])), old_normals[i]) >= cos_turn_;
    }
    // Better worst triangle, or the same worst and a better mean.
    const bool better = after > before + 1e-9 || (after >= std::min(before, kSmoothingFloor) &&
                                                  after_sum > before_sum + kMinGain);
    if (!ok || !better) {
      std::copy(old, old + 3, pv);
      return false;
    }
    home_[size_t(v)] = new_home;
    for (size_t i = 0; i < star.size(); ++i) q_[size_t(star[i])] = new_q[i];
    mark_star(v);
    return true;
  }

  SurfaceMesh& m_;
  std::vector<int32_t>& home_;
  std::vector<uint8_t>& fixed_;
  std::vector<double>& size_;
  const SurfaceMesh& in_;
  const TriangleAdjacency& in_adj_;
  double cos_turn_ = 0;
  std::vector<std::vector<int32_t>> vt_;
  std::vector<int32_t> opp_;  ///< per triangle edge k: across(t, T[k], T[k + 1])
  double collapse_ratio_ = 0, split_ratio_ = 0;
  std::vector<uint8_t> dead_;  ///< collapsed vertices (empty until the first)
  std::vector<int32_t> na_, nb_, changed_;
  int pass_ = 1;
  std::vector<double> q_;             ///< gamma_k per triangle
  std::vector<uint8_t> block_inner_;  ///< find_block_inner()
  std::vector<int32_t> color_, by_color_, color_start_, inner_, block_start_;  ///< plan_smoothing()
  std::vector<int32_t> inner_tris_, tri_block_start_, border_tris_;            ///< plan_swaps()
  std::vector<int> recent_;      ///< per vertex: the last pass it changed in
  std::vector<uint8_t> region_;  ///< per vertex: may change (empty: all); restrict_to()
  // See PinSlack: pin_of_ is renumbered whenever given.
  std::vector<int32_t>* pin_of_ = nullptr;
  const std::vector<double>* input_h_ = nullptr;
  double pin_slack_ = 0;
};

}  // namespace

int32_t project_near(const double* q, int32_t start, const SurfaceMesh& input,
                     const TriangleAdjacency& adj, double* out) {
  auto dist2 = [&](int32_t t, double* x) {
    const int32_t* T = &input.triangles[3 * size_t(t)];
    return closest_point_on_triangle(q, &input.points[3 * size_t(T[0])],
                                     &input.points[3 * size_t(T[1])],
                                     &input.points[3 * size_t(T[2])], x);
  };
  double best_point[3];
  const double radius2 = dist2(start, best_point);
  double best = radius2;
  int32_t best_t = start;
  // Breadth-first over triangles within the start triangle's distance.
  thread_local std::vector<int32_t> queue;
  queue.assign(1, start);
  for (size_t i = 0; i < queue.size() && queue.size() < 512; ++i) {
    const int32_t t = queue[i];
    for (int k = 0; k < 3; ++k) {
      const int32_t o = adj.opposite[3 * size_t(t) + k];
      if (o < 0) continue;
      const int32_t u = o / 3;
      if (std::find(queue.begin(), queue.end(), u) != queue.end()) continue;
      double x[3];
      const double d = dist2(u, x);
      if (d > radius2) continue;
      queue.push_back(u);
      if (d < best) {
        best = d;
        best_t = u;
        std::copy(x, x + 3, best_point);
      }
    }
  }
  std::copy(best_point, best_point + 3, out);
  return best_t;
}

SurfaceOptimizeStats optimize_on_surface(SurfaceMesh& mesh, WallVertices& wall,
                                         const SurfaceMesh& input,
                                         const TriangleAdjacency& input_adj,
                                         const SurfaceOptimizeOptions& options,
                                         const std::vector<uint8_t>& start, const PinSlack* pins) {
  SurfaceOptimizeStats stats;
  Optimizer opt(mesh, wall.home, wall.fixed, wall.size, input, input_adj, options, pins,
                &wall.pin_of);
  if (!start.empty()) opt.start_from(start);
  if (!start.empty() && options.region_rings >= 0) opt.restrict_to(start, options.region_rings);
  for (int pass = 0; pass < options.passes; ++pass) {
    size_t splits = pass < options.valence_passes ? opt.split_pass() : 0;
    size_t collapses = pass < options.valence_passes ? opt.collapse_pass() : 0;
    size_t swaps = pass < options.valence_passes ? opt.swap_pass(Optimizer::SwapGoal::kValence) : 0;
    swaps += opt.swap_pass(Optimizer::SwapGoal::kQuality);
    size_t moves = opt.smooth_pass();
    stats.collapses += collapses;
    stats.splits += splits;
    stats.swaps += swaps;
    stats.moves += moves;
    if (splits == 0 && collapses == 0 && swaps == 0 && moves == 0) break;
    opt.next_pass();
  }
  if (stats.collapses > 0) opt.compact(wall.fixed, wall.size);
  return stats;
}

}  // namespace vm
