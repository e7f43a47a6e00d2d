// Global optimization of the assembled surface mesh: edge swaps and
// smoothing with projection onto the input surface (Marchandise et al.,
// section 2.1, last step), which also heals the seams between patches.
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

struct SurfaceOptimizeOptions {
  int passes = 10;  ///< swap + smoothing passes
  /// The first passes also swap edges towards regular valences.
  int valence_passes = 10;
  /// A swap or a move is refused if it turns a triangle's normal by more
  /// than this (degrees), so the mesh cannot fold over sharp features.
  double max_normal_turn_degrees = 40;
  /// Interior edges shorter than this times the target size are collapsed
  /// (when sizes are given).
  double collapse_ratio = 0.7;
  /// Interior edges longer than this times the target size are split at
  /// their midpoint projected onto the input (when sizes are given; 0 = no
  /// split).
  double split_ratio = 1.6;
  /// With `start` flags: only the vertices within this many rings of the
  /// flagged ones change (move, or have a triangle swapped, split or
  /// collapsed), so that a local change stays local (-1: anywhere the
  /// passes carry it).
  int region_rings = -1;
};

/// Pinned vertices that may slide (see pin_to_input); the input vertex
/// each is pinned to is WallVertices::pin_of.
struct PinSlack {
  /// Per input vertex, the size h there (> 0).
  const std::vector<double>* input_h = nullptr;
  /// A pinned vertex may move, like a free one, while it stays within
  /// slack h of its input vertex (0: never).
  double slack = 0;
};

/// Values of the `fixed` flags of optimize_on_surface.
inline constexpr uint8_t kFree = 0;       ///< may move
inline constexpr uint8_t kOnOpening = 1;  ///< on an opening: never moves
inline constexpr uint8_t kOnFeature = 2;  ///< on a sharp crease: never moves
/// Pinned to an input vertex the output must pass through (see
/// pin_to_input): moves only within PinSlack::slack of it, and its edges
/// are not creases.
inline constexpr uint8_t kPinned = 3;

/// What travels with each vertex of the remeshed wall while it is
/// optimized and pinned: flat arrays, one entry per output vertex,
/// renumbered and extended together with the mesh.
struct WallVertices {
  std::vector<int32_t> home;    ///< an input triangle near (or containing) it
  std::vector<uint8_t> fixed;   ///< kFree, kOnOpening, kOnFeature or kPinned
  std::vector<int32_t> pin_of;  ///< the input vertex it is pinned to, or -1
  std::vector<double> size;     ///< target edge length there (model unit, > 0)
};

struct SurfaceOptimizeStats {
  size_t swaps = 0;
  size_t moves = 0;
  size_t collapses = 0;
  size_t splits = 0;
};

/// Improves `mesh` in place, in passes of five phases:
/// - splits of edges longer than `options.split_ratio` times the target size
///   at their midpoints projected onto `input`;
/// - collapses of edges shorter than `options.collapse_ratio` times the
///   target size `wall.size` (one per vertex; empty: no collapse), keeping the
///   mesh manifold (link condition) and the opening vertices in place;
/// - swaps of interior edges towards regular valences (6 inside, 4 on an
///   opening) that keep the pair's worst gamma_k above a fraction of itself;
/// - swaps that raise the smaller gamma_k of an edge's two triangles;
/// - moves of each vertex not `fixed` (or pinned, within its slack) to the
///   mean of the apexes that would make its triangles equilateral,
///   projected onto `input` (the closest point found by a walk from
///   `wall.home[v]`, an input triangle near v, which is updated), when the
///   star's worst gamma_k increases, or its mean increases while the worst
///   stays above min(before, 0.8).
/// Vertices only move to points of the input surface; the boundary edges of
/// `mesh` never change; no triangle turns by more than the normal guard.
/// Split vertices are appended (free) and collapsed vertices removed: mesh
/// and `wall` (home, fixed, size, and pin_of with `pins`) are renumbered
/// together. Preconditions: `mesh` is manifold and consistently oriented;
/// wall.home has one input triangle per vertex, wall.fixed one flag per
/// vertex (kOnOpening on every boundary vertex; kOnFeature, kPinned or
/// kFree elsewhere), wall.size one per vertex or empty (then no split or
/// collapse), wall.pin_of one per vertex with `pins`; input_adj is
/// build_adjacency(input).
/// `start` (empty, or one flag per vertex) limits the first pass to the
/// flagged vertices and their triangles; later passes follow the changes.
/// `pins` (null: none) lets pinned vertices slide (see PinSlack).
SurfaceOptimizeStats optimize_on_surface(SurfaceMesh& mesh, WallVertices& wall,
                                         const SurfaceMesh& input,
                                         const TriangleAdjacency& input_adj,
                                         const SurfaceOptimizeOptions& options = {},
                                         const std::vector<uint8_t>& start = {},
                                         const PinSlack* pins = nullptr);

/// The point of `input` closest to q (3 doubles) among the triangles reached
/// by a walk from triangle `start` over triangles no farther than `start`;
/// writes it to `out` and returns its triangle.
int32_t project_near(const double* q, int32_t start, const SurfaceMesh& input,
                     const TriangleAdjacency& input_adj, double* out);

}  // namespace vm
