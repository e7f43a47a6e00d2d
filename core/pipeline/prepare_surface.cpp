// Stage 1 of the pipeline (docs/ARCHITECTURE.md): read, weld, repair,
// recognise caps, analyze, decide the unit.
#include "core/pipeline/prepare_surface.h"

#include <algorithm>
#include <cstdio>

#include "core/layers/chord_radius.h"

namespace vm {
namespace {

std::string num(size_t n) { return std::to_string(n); }

std::string point_text(const std::array<double, 3>& p) {
  char buf[96];
  std::snprintf(buf, sizeof(buf), "(%.6g, %.6g, %.6g)", p[0], p[1], p[2]);
  return buf;
}

Status cancelled() { return Status::Cancelled(); }

/// A typical vessel radius of the prepared surface: the median radius of
/// its openings, else the median half chord across the lumen (closed
/// surfaces), else a tenth of the bounding box (too large to measure).
double median_vessel_radius(const PreparedSurface& s) {
  std::vector<double> radii;
  for (const Opening& op : s.topology.openings) radii.push_back(op.radius);
  if (radii.empty() && s.mesh.num_triangles() <= 2'000'000 && s.topology.components == 1 &&
      s.topology.nonmanifold_edges == 0)
    radii = chord_radius(s.mesh);
  if (radii.empty()) return 0.1 * s.box.diagonal();
  std::nth_element(radii.begin(), radii.begin() + long(radii.size() / 2), radii.end());
  return radii[radii.size() / 2];
}

}  // namespace

Result<PreparedSurface> prepare_surface(std::span<const uint8_t> file_bytes,
                                        const PrepareOptions& options, const ProgressFn& progress) {
  PreparedSurface s;
  if (!report_progress(progress, 0.0, "read")) return cancelled();
  SurfaceReadOptions read_options;
  read_options.max_triangles = options.read.max_triangles;
  Result<SurfaceFile> file = read_surface(file_bytes, read_options);
  if (!file.ok()) return file.status();
  s.ascii = file.value().soup.ascii;
  s.format = file.value().format;
  s.input_triangles = file.value().num_triangles();
  s.warnings = file.value().warnings;

  if (!report_progress(progress, 0.25, "weld")) return cancelled();
  // Face labels (per triangle) follow the triangles through every step.
  std::vector<int32_t> labels = std::move(file.value().face_labels);
  const std::vector<std::pair<int32_t, std::string>> face_names =
      std::move(file.value().face_names);
  s.label_array = file.value().label_array;
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
  remove_degenerate_and_duplicates(s.mesh, s.repair, &labels);
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

  if (options.largest_component_only) {
    const TopologyReport parts = analyze_topology(s.mesh, adjacency);
    if (parts.components > 1) {
      std::vector<uint8_t> other(s.mesh.num_triangles());
      for (size_t t = 0; t < other.size(); ++t) other[t] = parts.triangle_component[t] != 0;
      remove_triangles(s.mesh, other, &labels);
      adjacency = build_adjacency(s.mesh);
      s.warnings.push_back("kept the largest of " + std::to_string(parts.components) +
                           " components (" + num(parts.component_triangles[0]) + " of " +
                           num(parts.triangles) + " triangles)");
    }
  }

  if (!report_progress(progress, 0.55, "caps")) return cancelled();
  std::vector<int32_t> cap_of_vertex;  // recognised cap per vertex of the rims, else -1
  CapRecognition caps;
  if (!options.keep_caps && adjacency.num_nonmanifold_edges == 0 && s.repair.orientable) {
    caps = recognize_caps(s.mesh, adjacency, labels, face_names, options.caps);
    for (const std::string& note : caps.notes) s.warnings.push_back(note);
  }
  if (!caps.caps.empty()) {
    std::vector<uint8_t> remove(s.mesh.num_triangles(), 0);
    std::vector<int32_t> cap_of(s.mesh.num_vertices(), -1);
    for (size_t c = 0; c < caps.caps.size(); ++c)
      for (int32_t t : caps.caps[c].triangles) {
        remove[size_t(t)] = 1;
        for (int k = 0; k < 3; ++k)
          cap_of[size_t(s.mesh.triangles[3 * size_t(t) + k])] = int32_t(c);
      }
    const std::vector<int32_t> remap = remove_triangles(s.mesh, remove, &labels);
    cap_of_vertex.assign(s.mesh.num_vertices(), -1);
    for (size_t v = 0; v < remap.size(); ++v)
      if (remap[v] >= 0) cap_of_vertex[size_t(remap[v])] = cap_of[v];
    s.caps_removed = caps.caps.size();
    adjacency = build_adjacency(s.mesh);
    s.warnings.push_back(num(caps.caps.size()) + " planar caps were recognised and removed: " +
                         "their rims are openings now (keep them with {keep_caps})");
  }

  if (!report_progress(progress, 0.6, "analyze")) return cancelled();
  s.topology = analyze_topology(s.mesh, adjacency);
  for (const Opening& op : s.topology.openings) {
    OpeningSource src;
    const int32_t c = cap_of_vertex.empty() ? -1 : cap_of_vertex[size_t(op.loop[0])];
    if (c >= 0) {
      src.cap = true;
      src.label = caps.caps[size_t(c)].label;
      src.name = caps.caps[size_t(c)].name;
    }
    s.opening_sources.push_back(src);
  }
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

  s.unit = decide_unit(options.units, median_vessel_radius(s));
  if (s.unit.guessed && s.unit.unit == LengthUnit::kM)
    s.warnings.push_back("the model is in metres (" + s.unit.reason +
                         "): lengths are read and written in metres; say otherwise with {units}");

  if (!report_progress(progress, 0.85, "quality")) return cancelled();
  s.quality = triangle_qualities(s.mesh);
  s.quality_stats = quality_stats(s.quality, options.histogram_bins);
  if (!report_progress(progress, 1.0, "done")) return cancelled();
  return s;
}

Status check_meshable(const PreparedSurface& s) {
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
  if (t.components > 1) {
    return Status::Error("cannot mesh: the surface has " + std::to_string(t.components) +
                         " connected components (the largest has " + num(t.component_triangles[0]) +
                         " of " + num(t.triangles) +
                         " triangles); keep only the largest ({largest_component}) or clean the "
                         "segmentation");
  }
  return Status::Ok();
}

}  // namespace vm
