// The whole job (DESIGN.md pipeline): stage 1 (prepare), stages 2-3 (surface
// remeshing) and stage 7 (write); the surface is written as the `wall` group.
#include "core/pipeline/mesh_job.h"

#include <algorithm>
#include <chrono>

#include "core/mesh/self_intersection.h"
#include "core/mesh/surface_distance.h"

namespace vm {

Result<MeshJobResult> run_mesh_job(std::span<const uint8_t> stl_bytes,
                                   const MeshJobOptions& options, const ProgressFn& progress) {
  auto t0 = std::chrono::steady_clock::now();
  MeshJobResult r;
  // Stage 1 takes the first fifth of the progress bar, remeshing most of the rest.
  ProgressFn sub = [&](double f, std::string_view stage) {
    return report_progress(progress, 0.2 * f, stage);
  };
  Result<PreparedSurface> prepared = prepare_surface(stl_bytes, options.prepare, sub);
  if (!prepared.ok()) return prepared.status();
  r.surface = std::move(prepared).value();
  r.warnings = r.surface.warnings;

  const TopologyReport& topo = r.surface.topology;
  Status meshable = check_meshable(r.surface, options.largest_component_only);
  if (!meshable.ok()) return meshable;
  if (options.largest_component_only && topo.components > 1) {
    r.output_surface = extract_component(r.surface.mesh, topo, 0);
    r.warnings.push_back("kept the largest of " + std::to_string(topo.components) +
                         " components (" + std::to_string(topo.component_triangles[0]) +
                         " triangles)");
  } else {
    r.output_surface = r.surface.mesh;
  }
  if (options.remesh) {
    ProgressFn remesh_progress = [&](double f, std::string_view stage) {
      return report_progress(progress, 0.2 + 0.7 * f, stage);
    };
    const TopologyReport in = analyze_topology(r.output_surface);
    auto remeshed =
        remesh_surface(r.output_surface, options.remesh_options, &r.remesh_stats, remesh_progress);
    if (!remeshed.ok()) return remeshed.status();
    const SurfaceMesh input = std::move(r.output_surface);
    r.output_surface = std::move(remeshed.value().mesh);
    r.remeshed = true;
    // Fidelity: output vertices on the input, input vertices near the output.
    r.fidelity.max_vertex_offset = distances_to_surface(input, r.output_surface.points).max /
                                   bounding_box(input.points).diagonal();
    const DistanceReport gaps = distances_to_surface(r.output_surface, input.points, true);
    for (size_t v = 0; v < gaps.per_point.size(); ++v) {
      const double rel = gaps.per_point[v] / remeshed.value().input_sizes[v];
      r.fidelity.max_input_gap = std::max(r.fidelity.max_input_gap, rel);
      r.fidelity.input_gap_vertices += rel > 0.1;
    }
    // Never write a surface whose topology differs from the input's.
    r.output_topology = analyze_topology(r.output_surface);
    const TopologyReport& out = r.output_topology;
    if (out.components != in.components || out.genus != in.genus ||
        out.openings.size() != in.openings.size() || out.nonmanifold_edges > 0 ||
        out.nonmanifold_vertices > 0)
      return Status::Error(
          "the remeshed surface lost the input's topology (genus " + std::to_string(in.genus) +
          " -> " + std::to_string(out.genus) + ", openings " + std::to_string(in.openings.size()) +
          " -> " + std::to_string(out.openings.size()) + ", non-manifold edges " +
          std::to_string(out.nonmanifold_edges) +
          "): the size is too coarse for some feature; try a smaller --size or a larger "
          "--per-circumference");
    r.fidelity.self_intersections = find_self_intersections(r.output_surface, 0).pairs;
    if (r.fidelity.self_intersections > 0)
      r.warnings.push_back("the remeshed surface intersects itself (" +
                           std::to_string(r.fidelity.self_intersections) +
                           " pairs of triangles): try a smaller size");
  }

  if (!report_progress(progress, 0.9, "quality")) return Status::Error(kCancelledMessage);
  r.output_quality = triangle_qualities(r.output_surface);
  r.output_quality_stats = quality_stats(r.output_quality, options.prepare.histogram_bins);

  if (!report_progress(progress, 0.95, "write")) return Status::Error(kCancelledMessage);
  MshModel model;
  model.points = r.output_surface.points;
  model.physicals.push_back({2, 1, "wall"});
  MshBlock wall;
  wall.type = MshElementType::kTriangle;
  wall.entity_tag = 1;
  wall.physical_tag = 1;
  wall.nodes = r.output_surface.triangles;
  model.blocks.push_back(std::move(wall));
  for (const MshPhysical& ph : model.physicals) {
    OutputGroup g{ph.dim, ph.name, 0};
    for (const MshBlock& b : model.blocks)
      if (b.physical_tag == ph.tag && element_dimension(b.type) == ph.dim)
        g.elements += b.nodes.size() / size_t(nodes_per_element(b.type));
    r.groups.push_back(g);
  }
  Result<std::string> text = write_msh(model, options.msh_version);
  if (!text.ok()) return text.status();
  r.msh = std::move(text).value();
  report_progress(progress, 1.0, "done");
  r.seconds_total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace vm
