// Edge removal (Shewchuk, "Two discrete optimization algorithms for the
// topological improvement of tetrahedral meshes", 2002): the n tetrahedra
// around an edge (a, b) are replaced by the 2 (n - 2) tetrahedra over a
// triangulation of its ring polygon, triangle (x, y, z) of ring vertices (in
// ring order) giving (x, y, z, b) and (y, x, z, a) (ring_triangle_tets(),
// core/volume/tet_topology.h). This file chooses the triangulation: the one
// whose smallest triangle quality (a triangle's quality: the smaller of its
// two tetrahedra's, in the caller's measure) is largest, among every
// triangulation of the ring, by Klincsek's dynamic program ("Minimal
// triangulations of polygonal domains", Annals of Discrete Mathematics 9,
// 1980), or among the n fans from one ring vertex.
//
// The one routine of both edge removals: the Delaunay kernel's
// (Delaunay3D::remove_edge(), for boundary recovery: fans, any ring size,
// ghost tetrahedra allowed, each new tetrahedron checked exactly, its volume
// over its longest edge cubed) and the optimizer's (the flip pass of
// optimize_volume: every triangulation of rings up to kMaxProgramRing,
// gamma_t computed from what a triangle's tetrahedra share). The candidates
// and the measure are the callers' policies, given as parameters: each
// gives the triangulations (and so the meshes) it always gave.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/volume/tet_topology.h"

namespace vm {

/// Which triangulations of the ring are candidates.
enum class RingCandidates {
  /// Every triangulation (Klincsek's dynamic program): n <= kMaxProgramRing.
  kAll,
  /// The fans from ring vertex s = 0, 1, ..., n - 1 (just s = 0 for n = 3):
  /// triangles (s, s + i, s + i + 1) mod n, i = 1 .. n - 2. Any n.
  kFans,
};

/// The largest ring the dynamic program takes.
constexpr int kMaxProgramRing = 8;

/// A triangle of the ring polygon: three ring indices, in ring order.
using RingTriangle = std::array<int, 3>;

/// The triangulation of an n-vertex ring polygon (n >= 3) among
/// `candidates` whose smallest triangle quality is largest, and above
/// `floor`. quality(x, y, z, bound): the quality of the triangle of ring
/// indices x, y, z (in ring order; for kAll x < y < z), or any value <=
/// bound when it is not above bound (so that the measure may stop early; a
/// triangle that may not be used: -HUGE_VAL). Returns that smallest
/// quality, or a value <= floor when no candidate is above floor (tris then
/// empty). Ties go to the first candidate: for kAll, the dynamic program's
/// smallest apex k of each sub-polygon (i, j); for kFans the first s. The
/// n - 2 triangles into *tris (if not null): for kAll depth first from the
/// edge (0, n - 1), for kFans in fan order. Without tris, kAll stops early
/// (returning a value <= floor) once no triangulation can beat floor.
template <class Quality>
double best_ring_triangulation(int n, RingCandidates candidates, double floor, Quality&& quality,
                               std::vector<RingTriangle>* tris) {
  if (tris) tris->clear();
  if (candidates == RingCandidates::kFans) {
    double best_q = floor;
    int best_s = -1;
    for (int s = 0; s < (n == 3 ? 1 : n); ++s) {
      double q = 1e300;
      for (int i = 1; i + 1 < n && q > best_q; ++i)
        q = std::min(q, quality(s, (s + i) % n, (s + i + 1) % n, best_q));
      if (q > best_q) best_q = q, best_s = s;
    }
    if (best_s < 0) return -HUGE_VAL;
    if (tris)
      for (int i = 1; i + 1 < n; ++i)
        tris->push_back({best_s, (best_s + i) % n, (best_s + i + 1) % n});
    return best_q;
  }
  if (n > kMaxProgramRing) return -HUGE_VAL;
  // best[i][j]: the best smallest quality of a triangulation of the
  // sub-polygon i, i + 1, ..., j (1e300 for an edge); arg[i][j] its apex.
  // A triangle (or sub-polygon) whose quality is not above floor is never
  // part of an answer above floor, so it is dropped at once.
  constexpr double kNone = -1e300;
  double best[kMaxProgramRing][kMaxProgramRing];
  int arg[kMaxProgramRing][kMaxProgramRing];
  for (int i = 0; i + 1 < n; ++i) best[i][i + 1] = 1e300;
  for (int len = 2; len < n; ++len)
    for (int i = 0; i + len < n; ++i) {
      const int j = i + len;
      double bij = kNone;
      int aij = -1;
      for (int k = i + 1; k < j; ++k) {
        const double sub_q = std::min(best[i][k], best[k][j]);
        if (sub_q <= bij || sub_q <= floor) continue;
        double q = quality(i, k, j, std::max(bij, floor));
        q = std::min(q, sub_q);
        if (q <= bij || q <= floor) continue;
        bij = q;
        aij = k;
      }
      best[i][j] = bij;
      arg[i][j] = aij;
    }
  const double result = best[0][n - 1];
  if (tris && result > floor) {
    int stack[2 * kMaxProgramRing][2], top = 0;
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

/// The 2 tris.size() tetrahedra replacing edge (a, b) of ring `ring` (ring
/// vertex ids, as edge_ring() lists them) by the triangulation `tris`, in
/// its order: per triangle, ring_triangle_tets()'s two. Into out[0 ..].
inline void ring_removal_tets(int32_t a, int32_t b, const int32_t* ring,
                              const std::vector<RingTriangle>& tris, std::array<int32_t, 4>* out) {
  for (const RingTriangle& t : tris) {
    ring_triangle_tets(a, b, ring[t[0]], ring[t[1]], ring[t[2]], out);
    out += 2;
  }
}

}  // namespace vm
