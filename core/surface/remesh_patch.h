// Remeshing one parametrizable patch through its conformal map
// (Marchandise et al., section 2.1 and Fig. 2, steps 2-4).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/mesh2d/delaunay_refinement.h"
#include "core/util/result.h"

namespace vm {

/// Target edge length at a 3D point (3 doubles); must be > 0.
using PointSizeFn = std::function<double(const double* x)>;

struct PatchRemeshStats {
  size_t flipped_in_map = 0;   ///< parametric triangles folded by the map
  size_t boundary_points = 0;  ///< points on the resampled boundary
  double min_conformal_factor = 0, max_conformal_factor = 0;  ///< uv / 3D length
};

/// The planar mesher of the parameter plane (seed Table 1 rows).
enum class Mesher2D { kFrontal, kDelaunay, kAdapt };

struct PatchMeshOptions {
  Mesher2D mesher = Mesher2D::kFrontal;
  RefinementOptions refinement;
  int optimize_passes = 3;  ///< flips + smoothing passes in the plane
};

/// A point of a patch boundary: on the patch edge from local vertex a to b at
/// fraction t of its length (t = 0: vertex a itself).
struct PatchBoundaryPoint {
  int32_t a = -1, b = -1;
  double t = 0;
};

/// The remeshed patch: vertices 0 .. boundary.size() - 1 are the given
/// boundary points in order, the others new interior points; home[v] is a
/// patch triangle that contains vertex v.
struct PatchMesh {
  SurfaceMesh mesh;
  std::vector<int32_t> home;
};

/// Meshes a mapped disk-like patch: `uv` (2 per vertex, not folded) is its
/// parametrization, `vertex_size` (one per vertex, > 0) the target edge
/// length in 3D, interpolated linearly; `boundary` the discretization of
/// its single boundary loop, in loop order. The planar mesher runs with the
/// size scaled by the map's conformal factor, the planar mesh is optimized,
/// and every vertex is mapped back by barycentric interpolation, so it lies
/// on the patch. Triangles are oriented like the patch.
/// Errors: those of the planar mesher.
Result<PatchMesh> mesh_mapped_patch(const SurfaceMesh& patch, const std::vector<double>& uv,
                                    const std::vector<double>& vertex_size,
                                    const std::vector<PatchBoundaryPoint>& boundary,
                                    const PatchMeshOptions& options = {});

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
Result<SurfaceMesh> remesh_disk_patch(const SurfaceMesh& patch, const PointSizeFn& size,
                                      PatchRemeshStats* stats = nullptr,
                                      const PatchMeshOptions& options = {});

}  // namespace vm
