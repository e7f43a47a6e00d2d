// Partition of a surface into patches that a conformal map can flatten
// (Marchandise et al., section 2.1: "the surface is split into patches that
// are topological disks of moderate aspect ratio, so that the map does not
// crowd coordinates together").
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"
#include "core/param/lscm.h"
#include "core/util/result.h"

namespace vm {

/// A parametrization of a disk-like patch (lscm, map_to_disk, ...).
using PatchMapFn = std::function<Result<Parametrization>(const SurfaceMesh& patch)>;

struct PartitionOptions {
  /// Patches above this many triangles are split before being mapped.
  size_t max_patch_triangles = 40000;
  /// A map whose conformal factor (uv length / 3D length) varies more than
  /// this between its 2nd and 98th percentile triangles crowds coordinates:
  /// the patch is split further.
  double max_factor_ratio = 6.0;
  /// Bisection depth limit (an error beyond it).
  int max_depth = 48;
  /// Optional, one per input triangle (or empty): a patch must have fewer
  /// triangles than this at each of its triangles (0 = no limit). Used to
  /// split again a patch whose planar meshing failed.
  std::vector<int32_t> size_limit;
};

/// One patch with its parametrization.
struct MappedPatch {
  SurfaceMesh mesh;                  ///< the patch, with local vertex numbers
  std::vector<int32_t> vertex_of;    ///< local vertex -> input vertex
  std::vector<int32_t> triangle_of;  ///< local triangle -> input triangle
  Parametrization map;               ///< uv of the local vertices
  double factor_ratio = 1;           ///< the measured crowding (see options)
  /// Why no usable map was found for this disk ("" when `map` is one): it
  /// is to be remeshed without a map (isotropic_remesh_patch).
  std::string unmappable;
};

struct PartitionStats {
  size_t bisections = 0;
  size_t rejected_maps = 0;  ///< maps that folded or crowded, so split again
};

/// Splits `mesh` (manifold, consistently oriented) into patches that are
/// topological disks (connected, one boundary loop, Euler characteristic 1,
/// no pinched vertex) whose map by `map` neither folds nor crowds: a
/// candidate that fails is bisected by the plane through its area-weighted
/// median normal to its principal axis, the cut is straightened by moving
/// teeth (triangles with two neighbors across it) to the other side, and
/// each connected piece is tried again. Every input triangle ends in exactly
/// one patch. A map that fails is split further like one that folds; a
/// disk under 8 triangles whose map fails, or a disk at the depth limit
/// whose map still fails, folds or crowds, is a patch marked `unmappable`.
/// Errors: the depth limit on a piece that is not a disk.
Result<std::vector<MappedPatch>> partition_for_maps(const SurfaceMesh& mesh,
                                                    const TriangleAdjacency& adj,
                                                    const PatchMapFn& map,
                                                    const PartitionOptions& options = {},
                                                    PartitionStats* stats = nullptr);

/// The 2nd-to-98th percentile ratio of the per-triangle conformal factor
/// sqrt(uv area / 3D area) of a map (1 for a similarity).
double conformal_factor_ratio(const SurfaceMesh& patch, const std::vector<double>& uv);

/// Per-triangle conformal factor sqrt(uv area / 3D area) (0 where folded).
std::vector<double> conformal_factors(const SurfaceMesh& patch, const std::vector<double>& uv);

}  // namespace vm
