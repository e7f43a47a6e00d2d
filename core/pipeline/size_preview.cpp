// The size field a mesh job would ask for (size_preview.h).
#include "core/pipeline/size_preview.h"

#include "core/geom/vec3.h"
#include "core/pipeline/element_budget.h"
#include "core/surface/size_field.h"
#include "core/surface/vessel_radius.h"

namespace vm {

Status check_refine_sizes(const std::vector<RefineSphere>& spheres, double diagonal,
                          std::string_view unit) {
  const double smallest = 1e-4 * diagonal;
  for (const RefineSphere& s : spheres)
    if (!(s.size >= smallest))
      return Status::BadOption(
          "refine", "size " + number_text(s.size) + " at " +
                        point_text({s.center[0], s.center[1], s.center[2]}) + " " +
                        std::string(unit) + " is below 1e-4 of the model's size (" +
                        number_text(diagonal) + " " + std::string(unit) + "): give a size of " +
                        number_text(smallest, 2) + " or more");
  return Status::Ok();
}

Result<SizePreview> size_preview(const PreparedSurface& surface, const MeshJobOptions& options,
                                 std::span<const double> radius) {
  if (Status st = check_meshable(surface); !st.ok()) return st;
  const SizeOptions& so = options.remesh_options.size;
  if (Status st =
          check_refine_sizes(so.spheres, surface.box.diagonal(), unit_symbol(surface.unit.unit));
      !st.ok())
    return st;
  SizePreview p;
  if (radius.size() == surface.mesh.num_vertices())
    p.radius.assign(radius.begin(), radius.end());
  else
    p.radius = vessel_radius(surface.mesh);
  // The default size coarsened to the element budget as the job does.
  SizeOptions fitted = so;
  if (Status st = fit_element_budget(surface.mesh, surface.topology.openings, p.radius,
                                     element_budget(options), fitted, p.budget, &p.size);
      !st.ok())
    return st;
  return p;
}

}  // namespace vm
