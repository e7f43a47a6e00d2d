// Stage 1 of the pipeline: read a surface file, weld, repair and analyze it.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/io/read_surface.h"
#include "core/io/stl.h"
#include "core/mesh/repair.h"
#include "core/mesh/surface_mesh.h"
#include "core/mesh/topology.h"
#include "core/mesh/weld.h"
#include "core/quality/triangle_quality.h"
#include "core/util/progress.h"
#include "core/util/result.h"

namespace vm {

struct PrepareOptions {
  StlReadOptions read;
  WeldOptions weld;
  int histogram_bins = 20;
};

/// The welded, repaired surface and everything known about it.
struct PreparedSurface {
  SurfaceMesh mesh;
  bool ascii = false;          ///< ASCII STL
  std::string format;          ///< what was read (SurfaceFile::format), e.g. "binary STL"
  size_t input_triangles = 0;  ///< triangles in the file
  WeldStats weld;
  RepairStats repair;
  TopologyReport topology;
  BoundingBox box;
  std::vector<float> quality;  ///< gamma_k per triangle of `mesh`
  QualityStats quality_stats;
  /// Human-readable notes on the safe repairs applied and on properties that
  /// later stages will refuse (non-manifold edges, several components).
  std::vector<std::string> warnings;
};

/// Reads `stl_bytes` (any format read_surface reads, despite the name) and
/// prepares the surface. Errors are the reader's, or
/// "no triangle left" when every triangle was degenerate.
Result<PreparedSurface> prepare_surface(std::span<const uint8_t> stl_bytes,
                                        const PrepareOptions& options = {},
                                        const ProgressFn& progress = {});

/// Checks that a prepared surface can be meshed: manifold, orientable, and
/// one component unless `several_components_ok` (the caller then keeps the
/// largest). The error message says what is wrong, where, and what to do.
Status check_meshable(const PreparedSurface& surface, bool several_components_ok = false);

}  // namespace vm
