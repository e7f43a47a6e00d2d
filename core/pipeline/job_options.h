// Mesh-job options set by name, shared by the CLI (--name value) and the
// WebAssembly API ({name: value}) so both validate alike.
#pragma once

#include <string_view>
#include <vector>

#include "core/pipeline/mesh_job.h"
#include "core/util/result.h"

namespace vm {

/// The option names accepted by set_job_option, for usage text and checks.
const std::vector<std::string_view>& job_option_names();

/// Sets one option from text. Names (value):
///   size (h > 0, uniform mode), per-circumference (N >= 3, radius-adaptive
///   mode, the default with N = 20), size-min, size-max (>= 0), gradation
///   (>= 0), curvature (points per radian, >= 0), param
///   (lscm|harmonic|floater), mesher2d (frontal|delaunay|adapt),
///   msh-version (4.1|2.2).
/// Errors name the option and say what it needs.
Status set_job_option(MeshJobOptions& options, std::string_view name, std::string_view value);

}  // namespace vm
