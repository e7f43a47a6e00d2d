// Remeshing one patch on its own triangles in 3D, without a map: the
// fallback for a patch whose conformal map or planar meshing fails (a
// folded or self-crossing surface). Isotropic remeshing by edge splits,
// collapses, flips and smoothing projected onto the patch (Botsch and
// Kobbelt, "A remeshing approach to multiresolution modeling", SGP 2004),
// with the patch's boundary replaced by its shared samples first, so that
// the patch's neighbours stay conforming.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/surface/remesh_patch.h"
#include "core/util/result.h"

namespace vm {

struct IsotropicRemeshOptions {
  /// Passes of splits, collapses, flips and smoothing (each stops early
  /// when nothing changes).
  int passes = 30;
  /// Botsch and Kobbelt's limits: edges longer than split_ratio times the
  /// target size are split, shorter than collapse_ratio times it collapsed.
  double split_ratio = 4.0 / 3.0, collapse_ratio = 0.8;
};

struct IsotropicRemeshStats {
  /// The patch's own boundary vertices that were not samples, removed by
  /// collapses along the boundary, and of those the collapses that folded
  /// a triangle (no fold-free one was left).
  size_t boundary_collapses = 0, forced_collapses = 0;
  /// Edges split before optimizing: interior edges joining two boundary
  /// samples, and those split to keep a boundary collapse manifold.
  size_t chord_splits = 0, link_splits = 0;
  size_t splits = 0, collapses = 0, swaps = 0, moves = 0;  ///< of the optimization
};

/// Remeshes the disk-like patch `patch` (manifold, one boundary loop, no
/// pinched vertex; oriented) at the target edge length `vertex_size` (one
/// per patch vertex, > 0, model unit), with the boundary `boundary`: points
/// on the patch's boundary edges in the loop's order (as for
/// mesh_mapped_patch: the loop runs along its triangles' half-edges), at
/// least 3. Phases: the points inserted into their edges; the other
/// boundary vertices collapsed into their neighbours along the boundary
/// (fold-free ones first); interior edges between two boundary points
/// split; then passes of splits, collapses, valence and quality flips and
/// smoothing on the patch (optimize_on_surface with the patch as the
/// input surface, the boundary points fixed). Every vertex lies on the
/// patch. Like mesh_mapped_patch, vertices 0 .. boundary.size() - 1 of the
/// result are the boundary points in order, and home[v] is a patch triangle
/// containing vertex v; its boundary is exactly the points' loop and its
/// triangles are oriented like the patch. Errors: a boundary point off the
/// patch's boundary, fewer than 3 of them, or (a bug) a result that is not
/// a disk on them.
Result<PatchMesh> isotropic_remesh_patch(const SurfaceMesh& patch,
                                         const std::vector<double>& vertex_size,
                                         const std::vector<PatchBoundaryPoint>& boundary,
                                         const IsotropicRemeshOptions& options = {},
                                         IsotropicRemeshStats* stats = nullptr);

}  // namespace vm
