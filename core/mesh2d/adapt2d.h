// Local-adaptation meshing of a planar domain: the "MeshAdapt" row of the
// seed's Table 1 (Marchandise et al., section 3), by local edge splits.
#pragma once

#include <vector>

#include "core/mesh2d/delaunay_refinement.h"

namespace vm {

/// Meshes the domain bounded by `segments` (as constrained_delaunay) by
/// local adaptation: starting from the triangulation of the boundary alone,
/// every interior edge longer than `options.size_tolerance` times the local
/// size is split at its midpoint (Delaunay insertion, so the mesh stays
/// constrained Delaunay), in passes, until none is left; the boundary is
/// kept as given (no point inside a segment's diametral circle, none within
/// 0.3 h of a vertex). Smoothing and swaps follow in optimize_mesh2d.
/// Errors: those of constrained_delaunay, a non-positive size, the safety
/// limit.
Result<Mesh2D> adapt_mesh2d(const std::vector<double>& points, const std::vector<int32_t>& segments,
                            const SizeField2D& size, const RefinementOptions& options = {});

}  // namespace vm
