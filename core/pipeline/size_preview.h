// The size field a mesh job would ask for, before meshing: the local vessel
// radius R and the target edge length h at each vertex of a prepared
// surface, from the job's own size options (the same code path as the
// remeshing stage: vertex_sizes of core/surface/size_field.h), for a view
// of them (`vesselmesh info --size-field`, the JS sizeField()).
#pragma once

#include <span>
#include <string_view>
#include <vector>

#include "core/geom/refine_sphere.h"
#include "core/pipeline/mesh_job.h"
#include "core/pipeline/prepare_surface.h"
#include "core/util/result.h"

namespace vm {

/// Per vertex of the prepared surface (surface.mesh.num_vertices() values
/// each, model units).
struct SizePreview {
  /// R: the radius of the maximal inscribed ball at the vertex
  /// (vessel_radius, shrinking balls).
  std::vector<double> radius;
  /// h: the edge length the remeshing asks for there (size mode, curvature,
  /// clamps {size_min} {size_max}, {refine} spheres, gradation, the default
  /// coarsened to the element budget), before the fidelity rounds make it
  /// finer where the wall would leave the input.
  std::vector<double> size;
  /// The default size coarsened to the element budget (element_budget.h).
  BudgetFit budget;
};

/// The size field `run_mesh_job` would remesh `surface` with under
/// `options` (options.remesh_options.size; the job's checks first: the
/// surface meshable, refinement sizes not absurdly small). Errors are the
/// job's, with the same options named. `radius`: R of an earlier preview of
/// the same surface (it does not depend on the options), or empty.
Result<SizePreview> size_preview(const PreparedSurface& surface, const MeshJobOptions& options,
                                 std::span<const double> radius = {});

/// Refinement spheres whose size H is below 1e-4 of the model's bounding-box
/// diagonal are refused (kBadOption {refine}): the graded field would ask
/// for elements too small to place in floating point near the centre (the
/// hostile corpus found 1e-300 to hang), and no vessel feature is that
/// small. `unit`: the model's unit symbol, for the message.
Status check_refine_sizes(const std::vector<RefineSphere>& spheres, double diagonal,
                          std::string_view unit);

}  // namespace vm
