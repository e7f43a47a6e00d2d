// Every check of a job's options that needs no surface, in one place, run
// before the preparation starts: so that a job never fails on its options
// halfway through (after minutes of remeshing), and whichever interface
// gave them (CLI, JS, a program filling MeshJobOptions) gets the same
// refusal. What only the surface can tell (an opening number beyond its
// openings, sizes against the model's size) is checked where it is known.
#pragma once

#include <optional>

#include "core/io/output_file.h"
#include "core/pipeline/mesh_job.h"
#include "core/util/result.h"

namespace vm {

/// Checks `options` as a whole: the sizes (a uniform size > 0, at least 3
/// elements a circumference, size_min <= size_max, refinement spheres of
/// positive radius and size), the first layer from a target y+ (not with
/// {first_layer}, with an {inlet_velocity}, with layers to size), a mesh
/// family (volume meshes only), binary MSH with version 2.2 (when `format` is
/// MSH or not known), and `format` (when known: the option, the output's
/// name or the preset's) against {surface_only}. Errors are
/// kBadOption, naming the option to change.
Status validate_options(const MeshJobOptions& options, std::optional<OutputFormat> format);

}  // namespace vm
