// Sliver removal and quality improvement of a tetrahedral mesh, measured by
// gamma_t of the seed paper (Marchandise et al., section 3; docs/
// ARCHITECTURE.md, stage 6: sliver removal by flips and smoothing).
//
// - Topological improvement (Shewchuk, "Two discrete optimization
//   algorithms for the topological improvement of tetrahedral meshes",
//   2002; Klingner and Shewchuk, "Aggressive tetrahedral mesh improvement",
//   IMR 2007): 2-3 face removal and edge removal, the edge's ring
//   re-triangulated by Klincsek's dynamic program ("Minimal triangulations
//   of polygonal domains", 1980) maximizing the smallest gamma_t; a change
//   is made only when it raises the smallest quality of the tetrahedra it
//   replaces (hence 3-2 and 4-4 flips are the ring sizes 3 and 4). The
//   three shorter edges of a tetrahedron are tried only when its faces and
//   three longer edges give no such change.
// - Smoothing of the free vertices (Freitag and Ollivier-Gooch, "Tetrahedral
//   mesh improvement using swapping and smoothing", IJNME 40, 1997: smart
//   Laplacian with a quality guard): each vertex moves toward the centroid
//   of its star (ODT-like, Chen and Xu 2004 / Alliez et al. 2005), with a
//   line search, when the sum of 1 / gamma_t over its star decreases and its
//   star's smallest quality does not fall below min(before, floor).
// - Sliver phase: the vertices of the tetrahedra still below
//   sliver_threshold climb the smallest quality of their star (gradient of
//   the worst tetrahedron, then small deterministic random perturbations,
//   each move kept only when the star's minimum rises), alternated with
//   flips.
// Fixed vertices (the boundary) never move and boundary / constrained faces
// are never removed (TetMesh enforces both). Every tetrahedron created or
// moved is checked with the exact orient3d: no inverted or flat element.
#pragma once

#include <cstdint>
#include <vector>

#include "core/quality/triangle_quality.h"
#include "core/util/progress.h"
#include "core/util/result.h"
#include "core/volume/tet_mesh.h"

namespace vm {

struct OptimizeOptions {
  /// Rounds of (flips, smoothing of every free vertex). One gives most of
  /// the gain (torus, 2M tetrahedra: mean 0.673 -> 0.743 with one, 0.755
  /// with three, at 2.2x the time).
  int passes = 1;
  /// Tetrahedra below this gamma_t get topological improvement each round.
  double flip_threshold = 0.4;
  /// Smoothing may lower a star's smallest quality down to
  /// min(before, smooth_floor) when the sum of 1 / gamma_t improves.
  double smooth_floor = 0.3;
  /// Only vertices whose star's smallest quality is below this are
  /// smoothed (1: all).
  double smooth_below = 1.0;
  /// Sliver phase: work on tetrahedra below this gamma_t ...
  double sliver_threshold = 0.25;
  /// ... for at most this many rounds (aortic arch at h = 0.06, core
  /// 0.084: smallest gamma_t 0.230 with 8, 0.245 with 12, 0.248 with 16;
  /// the later rounds see few tetrahedra).
  int sliver_rounds = 16;
  /// Seed of the deterministic perturbations.
  uint64_t seed = 0x853c49e6748fea9bull;
};

struct OptimizeStats {
  QualityStats before, after;     ///< gamma_t, 20 bins
  int64_t topology_attempts = 0;  ///< tetrahedra examined for flips
  int64_t flips23 = 0;            ///< 2-3 face removals
  int64_t edge_removals = 0;      ///< ring of n >= 3 (3-2, 4-4, 5-6, ...)
  int64_t smoothing_moves = 0;
  int64_t sliver_moves = 0;  ///< gradient and perturbation moves
  int64_t insertions = 0;    ///< vertices inserted near stubborn slivers
  double flip_seconds = 0, smooth_seconds = 0, sliver_seconds = 0, seconds = 0;
};

/// Improves `mesh` in place. vertex_h: h per vertex (model units, > 0),
/// the scale of perturbations. Errors: size mismatch, cancelled.
Status optimize_volume(TetMesh& mesh, const std::vector<double>& vertex_h,
                       const OptimizeOptions& options, OptimizeStats* stats,
                       const ProgressFn& progress = {});

}  // namespace vm
