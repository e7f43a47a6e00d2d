// The volume stage of the pipeline after boundary recovery (docs/
// ARCHITECTURE.md, stage 6; Marchandise et al., section 2.2: "a three-dimensional Delaunay mesh
// generator is called to fill the remaining of the lumen volume with
// isotropic tetrahedra", measured by gamma_t of section 3): the size field
// graded from the surface (size_field3d.h), refinement of the recovered
// region (refine_volume.h), sliver removal and smoothing (optimize_volume.h)
// and the extraction of the volume mesh.
#pragma once

#include <cstdint>
#include <vector>

#include "core/geom/refine_sphere.h"
#include "core/mesh/volume_mesh.h"
#include "core/quality/triangle_quality.h"
#include "core/util/progress.h"
#include "core/util/result.h"
#include "core/volume/delaunay3d.h"
#include "core/volume/optimize_volume.h"
#include "core/volume/refine_volume.h"

namespace vm {

struct FillOptions {
  /// Tag of the region to fill (boundary recovery tags the inside 1).
  int32_t region_tag = 1;
  /// Core size H (model units, 0: no cap) and gradation g of the size field
  /// h(x) = min(H, min_i (h_i + g |x - x_i|)) (size_field3d.h).
  double core_size = 0;
  double gradation = 0.25;
  /// Local refinement spheres (refine_sphere.h) in the size field.
  std::vector<RefineSphere> spheres;
  /// Refinement options (region_tag is taken from above).
  RefineOptions refine;
  /// Optimization options; optimize = false skips the stage (for tests and
  /// benchmarks of the refinement alone).
  OptimizeOptions optimize_options;
  bool optimize = true;
};

struct FillStats {
  size_t boundary_vertices = 0;  ///< initial vertices used by the region
  size_t unused_vertices = 0;    ///< initial kernel vertices not in the region
  size_t inserted_vertices = 0;
  size_t tets = 0;
  RefineStats refine;
  OptimizeStats optimize;
  double size_field_seconds = 0, refine_seconds = 0, extract_seconds = 0, optimize_seconds = 0,
         seconds = 0;
};

/// Fills the region of `kernel` tagged options.region_tag with tetrahedra
/// of size h(x).
///
/// Input (the contract of boundary recovery): the region is closed by
/// constrained faces (set on both sides) and tagged region_tag, the rest
/// tagged otherwise; vertex_size holds one target size per kernel vertex
/// (model units; > 0 and finite for the vertices of the region, others
/// ignored). The region's vertices are the boundary: never moved, and no
/// constrained face is split or removed.
///
/// Output: points = the kernel's initial vertices used by the region in
/// their original order (the same indices as in the kernel when every
/// initial vertex is used, the normal case: unused_vertices = 0), then the
/// new interior vertices; tets positive (tet_volume6 > 0), tet_region 0;
/// triangles and prisms empty (the caller owns the surface and its tags).
/// The kernel is left refined (the new points inserted) but not optimized.
/// Errors: empty region, region not closed by constrained faces, bad sizes
/// or options, cancelled (Status::Cancelled()).
Result<VolumeMesh> fill_volume(Delaunay3D& kernel, const std::vector<double>& vertex_size,
                               const FillOptions& options, FillStats* stats,
                               const ProgressFn& progress = {});

}  // namespace vm
