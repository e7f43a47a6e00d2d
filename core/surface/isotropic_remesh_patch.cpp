// The fallback patch remesher (isotropic_remesh_patch.h): Botsch and
// Kobbelt's isotropic remeshing (SGP 2004) on the patch itself, in phases:
//  1. the boundary points inserted into the patch's boundary edges;
//  2. the patch's other boundary vertices collapsed along the boundary into
//     a neighbour (our own: fold-free collapses first, the link condition
//     kept by splitting the edges that would break it), so the boundary is
//     the points' loop and nothing else;
//  3. interior edges joining two boundary points split (they could neither
//     flip nor split later: both ends are fixed);
//  4. splits, collapses, flips and smoothing projected onto the patch, by
//     the wall's own optimizer (optimize_on_surface) with the patch as the
//     input surface and the boundary points fixed;
//  5. the result numbered as the planar route numbers it, and checked.
#include "core/surface/isotropic_remesh_patch.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/surface/fidelity.h"
#include "core/surface/optimize_surface.h"

namespace vm {
namespace {

/// A collapse whose triangles turn by less than this (cosine of the angle
/// between their normals before and after, 60 degrees) is clean: among
/// clean ones the shorter edge goes first.
constexpr double kCleanTurn = 0.5;
/// Rounds of phase 2 (each removes at least one vertex, or ends it).
constexpr int kMaxBoundaryRounds = 100000;

/// The patch while its boundary is replaced (phases 1-3): triangles (-1:
/// removed), vertex stars, and per vertex a patch triangle containing it
/// (`home`) and its boundary point (`sample`, or -1).
class BoundaryWork {
 public:
  BoundaryWork(const SurfaceMesh& patch, const TriangleAdjacency& adj)
      : points(patch.points), tris(patch.triangles), patch_(patch), adj_(adj) {
    const size_t nv = patch.num_vertices();
    star.assign(nv, {});
    home.assign(nv, -1);
    sample.assign(nv, -1);
    for (size_t t = 0; t < patch.num_triangles(); ++t)
      for (int c = 0; c < 3; ++c) {
        const int32_t v = tris[3 * t + size_t(c)];
        star[size_t(v)].push_back(int32_t(t));
        if (home[size_t(v)] < 0) home[size_t(v)] = int32_t(t);
      }
  }

  const double* p(int32_t v) const { return &points[3 * size_t(v)]; }
  const int32_t* tri(int32_t t) const { return &tris[3 * size_t(t)]; }
  size_t num_vertices() const { return home.size(); }

  /// The live triangle with the directed edge a -> b, or -1.
  int32_t with_edge(int32_t a, int32_t b) const {
    for (int32_t t : star[size_t(a)]) {
      const int32_t* T = tri(t);
      for (int c = 0; c < 3; ++c)
        if (T[c] == a && T[(c + 1) % 3] == b) return t;
    }
    return -1;
  }
  /// The patch's own triangle with the directed edge a -> b (patch
  /// vertices), or -1.
  int32_t patch_triangle_with_edge(int32_t a, int32_t b) const {
    for (int32_t i = adj_.star_offsets[size_t(a)]; i < adj_.star_offsets[size_t(a) + 1]; ++i) {
      const int32_t t = adj_.star[size_t(i)];
      const int32_t* T = &patch_.triangles[3 * size_t(t)];
      for (int c = 0; c < 3; ++c)
        if (T[c] == a && T[(c + 1) % 3] == b) return t;
    }
    return -1;
  }
  bool interior_edge(int32_t a, int32_t b) const {
    return with_edge(a, b) >= 0 && with_edge(b, a) >= 0;
  }
  /// v's neighbour along the boundary after it (next) or before it (prev),
  /// or -1 when v is inside.
  int32_t next(int32_t v) const {
    for (int32_t t : star[size_t(v)]) {
      const int32_t w = after(t, v, 1);
      if (with_edge(w, v) < 0) return w;
    }
    return -1;
  }
  int32_t prev(int32_t v) const {
    for (int32_t t : star[size_t(v)]) {
      const int32_t u = after(t, v, 2);
      if (with_edge(v, u) < 0) return u;
    }
    return -1;
  }
  std::vector<int32_t> neighbours(int32_t v) const {
    std::vector<int32_t> out;
    for (int32_t t : star[size_t(v)])
      for (int c = 1; c < 3; ++c) {
        const int32_t w = after(t, v, c);
        if (std::find(out.begin(), out.end(), w) == out.end()) out.push_back(w);
      }
    return out;
  }

  /// The point of the patch nearest the midpoint of (a, b), found from a's
  /// home: splits edge {a, b} there (see split).
  int32_t split_at_midpoint(int32_t a, int32_t b) {
    const Vec3 mid = 0.5 * (at(points, a) + at(points, b));
    double x[3];
    const int32_t h = project_near(mid.data(), home[size_t(a)], patch_, adj_, x);
    return split(a, b, x, h);
  }

  /// Splits edge {a, b} (one or two triangles) at x, on patch triangle h:
  /// each triangle (s, e, c) with the edge becomes (s, m, c) and (m, e, c).
  int32_t split(int32_t a, int32_t b, const double* x, int32_t h) {
    const int32_t m = int32_t(num_vertices());
    points.insert(points.end(), x, x + 3);
    home.push_back(h);
    sample.push_back(-1);
    star.emplace_back();
    for (const auto& [s, e] : {std::array{a, b}, std::array{b, a}}) {
      const int32_t t = with_edge(s, e);
      if (t < 0) continue;
      const int32_t c = after(t, s, 2);
      remove_triangle(t);
      add_triangle(s, m, c);
      add_triangle(m, e, c);
    }
    return m;
  }

  /// Collapses v into its neighbour u: the triangles with both go, v's
  /// others take u.
  void collapse(int32_t v, int32_t u) {
    const std::vector<int32_t> around = star[size_t(v)];
    for (int32_t t : around) {
      const int32_t* T = tri(t);
      if (T[0] == u || T[1] == u || T[2] == u) remove_triangle(t);
    }
    for (int32_t t : star[size_t(v)]) {
      for (int c = 0; c < 3; ++c)
        if (tris[3 * size_t(t) + size_t(c)] == v) tris[3 * size_t(t) + size_t(c)] = u;
      star[size_t(u)].push_back(t);
    }
    star[size_t(v)].clear();
  }

  /// How little collapsing v into u turns v's other triangles: the least
  /// cosine between a triangle's unit normal before and after (-1 when one
  /// becomes degenerate; 1 when none is left).
  double collapse_turn(int32_t v, int32_t u) const {
    double worst = 1;
    for (int32_t t : star[size_t(v)]) {
      const int32_t* T = tri(t);
      if (T[0] == u || T[1] == u || T[2] == u) continue;
      Vec3 q[3];
      for (int c = 0; c < 3; ++c) q[c] = at(points, T[c]);
      const Vec3 before = cross(q[1] - q[0], q[2] - q[0]);
      for (int c = 0; c < 3; ++c)
        if (T[c] == v) q[c] = at(points, u);
      const Vec3 after = cross(q[1] - q[0], q[2] - q[0]);
      const double lb = norm(before), la = norm(after);
      if (!(lb > 0)) continue;  // degenerate already: nothing to lose
      worst = std::min(worst, la > 1e-12 * lb ? dot(before, after) / (lb * la) : -1.0);
    }
    return worst;
  }

  /// Makes collapsing v into its boundary neighbour u keep the patch a
  /// manifold disk (the link condition: their only common neighbour is the
  /// apex of their triangle): each other common neighbour y loses its edge
  /// to v, or (y, v being a boundary edge) to u, by a split.
  size_t keep_link(int32_t v, int32_t u) {
    const int32_t t = with_edge(v, u) >= 0 ? with_edge(v, u) : with_edge(u, v);
    const int32_t* T = tri(t);
    const int32_t apex = T[0] != u && T[0] != v ? T[0] : T[1] != u && T[1] != v ? T[1] : T[2];
    size_t splits = 0;
    const std::vector<int32_t> nu = neighbours(u);
    for (int32_t y : neighbours(v)) {
      if (y == u || y == apex || std::find(nu.begin(), nu.end(), y) == nu.end()) continue;
      if (interior_edge(v, y))
        split_at_midpoint(v, y);
      else
        split_at_midpoint(u, y);
      ++splits;
    }
    return splits;
  }

  std::vector<double> points;
  std::vector<int32_t> tris;
  std::vector<std::vector<int32_t>> star;
  std::vector<int32_t> home, sample;

 private:
  /// The corner `k` places after v in triangle t (1: next, 2: previous).
  int32_t after(int32_t t, int32_t v, int k) const {
    const int32_t* T = tri(t);
    int c = 0;
    while (T[c] != v) ++c;
    return T[(c + k) % 3];
  }
  void add_triangle(int32_t a, int32_t b, int32_t c) {
    const int32_t t = int32_t(tris.size() / 3);
    tris.insert(tris.end(), {a, b, c});
    for (int32_t v : {a, b, c}) star[size_t(v)].push_back(t);
  }
  void remove_triangle(int32_t t) {
    int32_t* T = &tris[3 * size_t(t)];
    for (int c = 0; c < 3; ++c) {
      auto& s = star[size_t(T[c])];
      s.erase(std::find(s.begin(), s.end(), t));
    }
    T[0] = T[1] = T[2] = -1;
  }

  const SurfaceMesh& patch_;
  const TriangleAdjacency& adj_;
};

/// Phase 1: every boundary point a vertex (at its patch vertex, or split
/// into its edge, points of one edge in order of t).
Status insert_boundary_points(BoundaryWork& w, const std::vector<PatchBoundaryPoint>& boundary) {
  for (size_t j = 0; j < boundary.size();) {
    const PatchBoundaryPoint& b = boundary[j];
    if (b.a < 0 || b.b < 0 || size_t(b.a) >= w.num_vertices() || size_t(b.b) >= w.num_vertices() ||
        w.with_edge(b.a, b.b) < 0 || w.with_edge(b.b, b.a) >= 0)
      return Status::Error("a patch boundary point is not on a boundary edge of the patch");
    if (b.t == 0) {
      w.sample[size_t(b.a)] = int32_t(j++);
      continue;
    }
    // Points on the edge (a, b), homed on its patch triangle.
    const int32_t home = w.patch_triangle_with_edge(b.a, b.b);
    int32_t from = b.a;
    for (; j < boundary.size() && boundary[j].a == b.a && boundary[j].b == b.b && boundary[j].t > 0;
         ++j) {
      const double t = boundary[j].t;
      const Vec3 x = (1 - t) * at(w.points, b.a) + t * at(w.points, b.b);
      const int32_t m = w.split(from, b.b, x.data(), home);
      w.sample[size_t(m)] = int32_t(j);
      from = m;
    }
  }
  return Status::Ok();
}

/// Phase 2: the boundary vertices that are not points, collapsed into a
/// neighbour along the boundary: in rounds over them in loop order, each
/// into the neighbour whose collapse turns its triangles least (clean ones,
/// under 60 degrees, into the nearer neighbour); a round that finds none
/// under 90 degrees collapses the least turning one anyway.
Status remove_other_boundary_vertices(BoundaryWork& w, int32_t start, IsotropicRemeshStats& stats) {
  for (int round = 0; round < kMaxBoundaryRounds; ++round) {
    std::vector<int32_t> others;
    for (int32_t v = start, steps = 0;; v = w.next(v)) {
      if (v < 0 || size_t(++steps) > w.num_vertices())
        return Status::Error("the patch's boundary is not one loop");
      if (w.sample[size_t(v)] < 0) others.push_back(v);
      if (w.next(v) == start) break;
    }
    if (others.empty()) return Status::Ok();
    // The best collapse of v: (into, turn).
    auto best_of = [&](int32_t v) {
      std::array<int32_t, 2> ends = {w.prev(v), w.next(v)};
      const double d0 = norm(at(w.points, ends[0]) - at(w.points, v)),
                   d1 = norm(at(w.points, ends[1]) - at(w.points, v));
      if (d1 < d0) std::swap(ends[0], ends[1]);  // the nearer first
      const double t0 = w.collapse_turn(v, ends[0]), t1 = w.collapse_turn(v, ends[1]);
      if (t0 >= kCleanTurn || t0 >= t1) return std::pair{ends[0], t0};
      return std::pair{ends[1], t1};
    };
    size_t collapsed = 0;
    for (int32_t v : others) {
      if (w.star[size_t(v)].empty() || w.next(v) < 0) continue;
      const auto [into, turn] = best_of(v);
      if (!(turn > 0)) continue;
      stats.link_splits += w.keep_link(v, into);
      w.collapse(v, into);
      ++collapsed;
    }
    stats.boundary_collapses += collapsed;
    if (collapsed > 0) continue;
    // None without a fold: the least turning one.
    int32_t worst_v = -1, worst_into = -1;
    double worst_turn = -2;
    for (int32_t v : others) {
      const auto [into, turn] = best_of(v);
      if (turn > worst_turn) worst_turn = turn, worst_v = v, worst_into = into;
    }
    stats.link_splits += w.keep_link(worst_v, worst_into);
    w.collapse(worst_v, worst_into);
    ++stats.boundary_collapses;
    ++stats.forced_collapses;
  }
  return Status::Error("the patch's boundary vertices could not be removed");
}

/// Phase 3: interior edges whose two ends are boundary points, split at
/// their midpoints on the patch (new triangles are visited too).
size_t split_chords(BoundaryWork& w) {
  size_t splits = 0;
  for (size_t t = 0; t < w.tris.size() / 3; ++t)
    for (int c = 0; c < 3 && w.tris[3 * t] >= 0; ++c) {
      const int32_t a = w.tris[3 * t + size_t(c)], b = w.tris[3 * t + size_t(c + 1) % 3];
      if (w.sample[size_t(a)] >= 0 && w.sample[size_t(b)] >= 0 && w.interior_edge(a, b)) {
        w.split_at_midpoint(a, b);
        ++splits;
      }
    }
  return splits;
}

/// Phase 5: the boundary of `m` is exactly the loop 0 -> 1 -> ... -> count
/// - 1 -> 0 of its first vertices, every vertex is used, and it is a disk.
Status check_disk_on_points(const SurfaceMesh& m, size_t count) {
  const TriangleAdjacency adj = build_adjacency(m);
  if (adj.num_nonmanifold_edges > 0) return Status::Internal("the fallback patch is not manifold");
  std::vector<int32_t> next(m.num_vertices(), -1);
  size_t boundary = 0;
  for (size_t h = 0; h < adj.opposite.size(); ++h)
    if (adj.opposite[h] == TriangleAdjacency::kBoundary) {
      const int32_t a = half_edge_from(m, int32_t(h));
      if (size_t(a) >= count || next[size_t(a)] >= 0)
        return Status::Internal("the fallback patch's boundary is not its points' loop");
      next[size_t(a)] = half_edge_to(m, int32_t(h));
      ++boundary;
    }
  for (size_t j = 0; j < count; ++j)
    if (next[j] != int32_t((j + 1) % count))
      return Status::Internal("the fallback patch's boundary is not its points' loop");
  std::vector<uint8_t> used(m.num_vertices(), 0);
  for (int32_t v : m.triangles) used[size_t(v)] = 1;
  const long chi = long(m.num_vertices()) - long(adj.num_edges) + long(m.num_triangles());
  if (boundary != count || std::count(used.begin(), used.end(), 0) > 0 || chi != 1)
    return Status::Internal("the fallback patch is not a disk");
  return Status::Ok();
}

}  // namespace

Result<PatchMesh> isotropic_remesh_patch(const SurfaceMesh& patch,
                                         const std::vector<double>& vertex_size,
                                         const std::vector<PatchBoundaryPoint>& boundary,
                                         const IsotropicRemeshOptions& options,
                                         IsotropicRemeshStats* stats_out) {
  IsotropicRemeshStats stats;
  const size_t count = boundary.size();
  if (count < 3) return Status::Error("a patch boundary has fewer than 3 points");
  const TriangleAdjacency adj = build_adjacency(patch);
  BoundaryWork w(patch, adj);
  // Phases 1-3.
  if (Status st = insert_boundary_points(w, boundary); !st.ok()) return st;
  int32_t start = -1;
  for (size_t v = 0; v < w.num_vertices() && start < 0; ++v)
    if (w.sample[v] == 0) start = int32_t(v);
  if (Status st = remove_other_boundary_vertices(w, start, stats); !st.ok()) return st;
  stats.chord_splits = split_chords(w);

  // Phase 4 on the live triangles, the boundary points numbered first (in
  // order), the other vertices after them in the order they have.
  std::vector<int32_t> number(w.num_vertices(), -1);
  for (size_t v = 0; v < w.num_vertices(); ++v)
    if (w.sample[v] >= 0) number[v] = w.sample[v];
  int32_t next_id = int32_t(count);
  for (size_t v = 0; v < w.num_vertices(); ++v)
    if (w.sample[v] < 0 && !w.star[v].empty()) number[v] = next_id++;
  PatchMesh out;
  SurfaceMesh& m = out.mesh;
  WallVertices wall;
  m.points.resize(3 * size_t(next_id));
  wall.home.resize(size_t(next_id));
  wall.fixed.assign(size_t(next_id), kFree);
  std::fill(wall.fixed.begin(), wall.fixed.begin() + long(count), kOnOpening);
  for (size_t v = 0; v < w.num_vertices(); ++v) {
    if (number[v] < 0) continue;
    put(m.points, number[v], at(w.points, int32_t(v)));
    wall.home[size_t(number[v])] = w.home[v];
  }
  for (size_t t = 0; t < w.tris.size() / 3; ++t)
    if (w.tris[3 * t] >= 0)
      for (int c = 0; c < 3; ++c) m.triangles.push_back(number[size_t(w.tris[3 * t + size_t(c)])]);
  wall.size = output_sizes(patch, wall.home, vertex_size);
  SurfaceOptimizeOptions so;
  so.passes = so.valence_passes = options.passes;
  so.split_ratio = options.split_ratio;
  so.collapse_ratio = options.collapse_ratio;
  const SurfaceOptimizeStats os = optimize_on_surface(m, wall, patch, adj, so);
  stats.splits = os.splits;
  stats.collapses = os.collapses;
  stats.swaps = os.swaps;
  stats.moves = os.moves;
  // Phase 5.
  if (Status st = check_disk_on_points(m, count); !st.ok()) return st;
  out.home = std::move(wall.home);
  if (stats_out) *stats_out = stats;
  return out;
}

}  // namespace vm
