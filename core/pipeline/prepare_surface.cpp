// Pipeline stage 1 (DESIGN.md): read, weld, repair, analyze.
#include "core/pipeline/prepare_surface.h"

#include <cstdio>

namespace vm {
namespace {

std::string num(size_t n) { return std::to_string(n); }

std::string point_text(const std::array<double, 3>& p) {
  char buf[96];
  std::snprintf(buf, sizeof(buf), "(%.6g, %.6g, %.6g)", p[0], p[1], p[2]);
  return buf;
}

Status cancelled() { return Status::Error(kCancelledMessage); }

}  // namespace

Result<PreparedSurface> prepare_surface(std::span<const uint8_t> stl_bytes,
                                        const PrepareOptions& options, const ProgressFn& progress) {
  PreparedSurface s;
  if (!report_progress(progress, 0.0, "read")) return cancelled();
  SurfaceReadOptions read_options;
  read_options.max_triangles = options.read.max_triangles;
  Result<SurfaceFile> file = read_surface(stl_bytes, read_options);
  if (!file.ok()) return file.status();
  s.ascii = file.value().soup.ascii;
  s.format = file.value().format;
  s.input_triangles = file.value().num_triangles();
  s.warnings = file.value().warnings;

  if (!report_progress(progress, 0.25, "weld")) return cancelled();
  if (!file.value().soup.coords.empty()) {
    s.mesh = weld(file.value().soup, options.weld, &s.weld);
  } else {
    s.mesh = weld(file.value().points, file.value().triangles, options.weld, &s.weld);
  }
  file = Result<SurfaceFile>::Error("released");  // free the file's arrays early
  if (s.weld.merged_by_tolerance > 0) {
    s.warnings.push_back(num(s.weld.merged_by_tolerance) +
                         " nearly coincident vertices were merged");
  }

  if (!report_progress(progress, 0.45, "repair")) return cancelled();
  remove_degenerate_and_duplicates(s.mesh, s.repair);
  if (s.repair.degenerate_removed > 0) {
    s.warnings.push_back(num(s.repair.degenerate_removed) + " zero-area triangles were removed");
  }
  if (s.repair.collinear_repaired > 0) {
    s.warnings.push_back(num(s.repair.collinear_repaired) +
                         " flat triangles (collinear corners) were removed by "
                         "splitting their neighbors");
  }
  if (s.repair.duplicates_removed > 0) {
    s.warnings.push_back(num(s.repair.duplicates_removed) + " duplicate triangles were removed");
  }
  if (s.mesh.num_triangles() == 0) {
    return Status::Error("no triangle left: all " + num(s.input_triangles) +
                         " triangles of the file have zero area");
  }
  TriangleAdjacency adjacency;
  orient_consistently(s.mesh, s.repair, &adjacency);
  if (!s.repair.orientable) {
    s.warnings.push_back("the surface is not orientable: it cannot bound a volume");
  } else if (s.repair.flipped == s.mesh.num_triangles()) {
    s.warnings.push_back("the normals pointed inward: all triangles were reversed to face out");
  } else if (s.repair.flipped > 0) {
    s.warnings.push_back(num(s.repair.flipped) +
                         " triangles were re-oriented (consistent, outward)");
  }

  if (!report_progress(progress, 0.6, "analyze")) return cancelled();
  s.topology = analyze_topology(s.mesh, adjacency);
  s.box = bounding_box(s.mesh.points);
  const TopologyReport& t = s.topology;
  if (t.nonmanifold_edges > 0) {
    s.warnings.push_back(num(t.nonmanifold_edges) +
                         " non-manifold edges (shared by 3 or more triangles), "
                         "e.g. near " +
                         point_text(t.nonmanifold_edge_example));
  }
  if (t.nonmanifold_vertices > 0) {
    s.warnings.push_back(num(t.nonmanifold_vertices) +
                         " non-manifold vertices (surface sheets touching at "
                         "a single vertex)");
  }
  if (t.components > 1) {
    s.warnings.push_back(std::to_string(t.components) + " connected components; the largest has " +
                         num(t.component_triangles[0]) + " of " + num(t.triangles) + " triangles");
  }

  if (!report_progress(progress, 0.85, "quality")) return cancelled();
  s.quality = triangle_qualities(s.mesh);
  s.quality_stats = quality_stats(s.quality, options.histogram_bins);
  if (!report_progress(progress, 1.0, "done")) return cancelled();
  return s;
}

Status check_meshable(const PreparedSurface& s, bool several_components_ok) {
  const TopologyReport& t = s.topology;
  if (t.nonmanifold_edges > 0) {
    return Status::Error("cannot mesh: the surface has " + num(t.nonmanifold_edges) +
                         " non-manifold edges (shared by 3 or more triangles), e.g. near " +
                         point_text(t.nonmanifold_edge_example) +
                         "; fix the segmentation or export a manifold surface");
  }
  if (t.nonmanifold_vertices > 0) {
    return Status::Error("cannot mesh: the surface has " + num(t.nonmanifold_vertices) +
                         " non-manifold vertices (sheets touching at a vertex)");
  }
  if (!s.repair.orientable) {
    return Status::Error("cannot mesh: the surface is not orientable");
  }
  if (t.components > 1 && !several_components_ok) {
    return Status::Error("cannot mesh: the surface has " + std::to_string(t.components) +
                         " connected components (the largest has " + num(t.component_triangles[0]) +
                         " of " + num(t.triangles) +
                         " triangles); keep only the largest (--largest-component) or clean the "
                         "segmentation");
  }
  return Status::Ok();
}

}  // namespace vm
