// The checks of a job's options before it starts (validate_options.h).
#include "core/pipeline/validate_options.h"

#include <cmath>
#include <string>

#include "core/pipeline/write_outputs.h"

namespace vm {
namespace {

Status check_sizes(const SizeOptions& o) {
  if (o.mode == SizeMode::kUniform && !(o.size > 0 && std::isfinite(o.size)))
    return Status::BadOption("size", "must be a positive number");
  if (o.mode == SizeMode::kPerCircumference &&
      !(o.per_circumference >= 3 && std::isfinite(o.per_circumference)))
    return Status::BadOption("per_circumference", "must be a number >= 3");
  if (!(o.size_min >= 0) || !(o.size_max > 0) || o.size_min > o.size_max)
    return Status::BadOption("size_min", "must be >= 0 and at most {size_max}");
  for (const RefineSphere& s : o.spheres)
    if (!(s.radius > 0) || !(s.size > 0) || !std::isfinite(s.radius) || !std::isfinite(s.size))
      return Status::BadOption("refine", "needs a positive radius R and size H");
  return Status::Ok();
}

Status check_yplus(const MeshJobOptions& options) {
  const YPlusTarget& t = options.yplus;
  if (!(t.yplus > 0)) return Status::Ok();
  if (options.viscous.first_height > 0)
    return Status::BadOption("first_layer_yplus",
                             "and {first_layer} both set the first layer's height: give one");
  if (!(t.velocity > 0))
    return Status::BadOption("first_layer_yplus",
                             "needs the flow's {inlet_velocity} (m/s) to size the first layer");
  if (options.viscous.layers <= 0 || !options.volume)
    return Status::BadOption("first_layer_yplus",
                             "sizes the boundary layer's first layer: there is none ({layers} 0 "
                             "or {surface_only})");
  return Status::Ok();
}

}  // namespace

Status validate_options(const MeshJobOptions& options, std::optional<OutputFormat> format) {
  if (Status st = check_sizes(options.remesh_options.size); !st.ok()) return st;
  if (Status st = check_yplus(options); !st.ok()) return st;
  if (options.family > 1 && !options.volume)
    return Status::BadOption("family",
                             "makes volume meshes for a convergence study: drop {surface_only}");
  if (!format || *format == OutputFormat::kMsh)
    if (auto encoding = msh_encoding(options.msh_version, options.msh_binary); !encoding.ok())
      return encoding.status();
  if (format && !options.volume && volume_format(*format))
    return Status::BadOption("format", "cannot be " + std::string(format_name(*format)) +
                                           ": it holds a volume mesh, and {surface_only} writes "
                                           "the wall alone; use msh, vtp or stl");
  return Status::Ok();
}

}  // namespace vm
