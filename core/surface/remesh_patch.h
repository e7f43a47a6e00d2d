// Remeshing one parametrizable patch through its conformal map
// (Marchandise et al., section 2.1 and Fig. 2, steps 2-4).
#pragma once

#include <functional>

#include "core/mesh/surface_mesh.h"
#include "core/mesh2d/delaunay_refinement.h"
#include "core/util/result.h"

namespace vm {

/// Target edge length at a 3D point (3 doubles); must be > 0.
using SizeField3D = std::function<double(const double* x)>;

struct PatchRemeshStats {
  size_t flipped_in_map = 0;   ///< parametric triangles folded by the map
  size_t boundary_points = 0;  ///< points on the resampled boundary
  double min_conformal_factor = 0, max_conformal_factor = 0;  ///< uv / 3D length
};

/// Remeshes a disk-like patch (genus 0, exactly one boundary loop): maps it
/// to the plane by the least-squares conformal map, resamples the boundary
/// loop in 3D at the target size (so a neighbor sharing it can do the same),
/// meshes the plane by Delaunay refinement with the size scaled by the local
/// conformal factor (the map preserves angles, so isotropic stays
/// isotropic), optimizes it there (flips, smoothing), and maps every new
/// vertex back by barycentric interpolation
/// in the parametric triangle containing it: every output vertex lies on the
/// input surface. Output triangles are oriented like the input.
/// Errors: not exactly one boundary loop, a folded map, a meshing failure.
Result<SurfaceMesh> remesh_disk_patch(const SurfaceMesh& patch, const SizeField3D& size,
                                      PatchRemeshStats* stats = nullptr,
                                      const RefinementOptions& options = {});

}  // namespace vm
