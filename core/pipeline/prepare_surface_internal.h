// What the phases of prepare_surface() (prepare_surface.h) share: the work
// they pass on besides the surface, and the phases called from another
// file than their own. The files: prepare_surface.cpp (phase 1, read and
// weld; phases 2e-4, the unit, the largest component, smoothing; phases
// 8-9, analysis and self-crossings; the entry points),
// prepare_surface_repair.cpp (phase 2, repairs) and
// prepare_surface_openings.cpp (phases 5-7: caps, cuts, flow extensions).
// Not part of the API.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh/topology.h"
#include "core/pipeline/prepare_surface.h"

namespace vm {
namespace prepare_surface_detail {

/// n in decimal.
inline std::string num(size_t n) { return std::to_string(n); }

/// What the phases pass on besides the surface: face labels (one per
/// triangle, or empty), the file's face names, the adjacency of the current
/// mesh, and where openings come from: per vertex an index into `sources`
/// (-1: an opening of the file, or no opening).
struct Work {
  std::vector<int32_t> labels;
  std::vector<std::pair<int32_t, std::string>> face_names;
  TriangleAdjacency adjacency;
  /// The topology of the current mesh when it is known (analyze_topology
  /// with `adjacency`); reset by every phase that changes the mesh.
  std::optional<TopologyReport> topology;
  std::vector<OpeningSource> sources;
  std::vector<int32_t> source_of_vertex;
  /// Set by flow extensions: per vertex, the opening it bounds in the
  /// order before extension (-1: none), which the analysis keeps (an
  /// extension keeps an opening's area, but ties could reorder).
  std::vector<int32_t> order_of_vertex;
  /// Where phase 4's note goes among the warnings (none: npos).
  size_t smoothing_note = std::string::npos;

  /// The topology of the current mesh, analyzed once.
  const TopologyReport& current_topology(const SurfaceMesh& mesh) {
    if (!topology) topology = analyze_topology(mesh, adjacency);
    return *topology;
  }

  /// After vertices were renumbered (old -> new, -1 removed).
  void remap_vertices(const std::vector<int32_t>& remap, size_t new_count) {
    if (source_of_vertex.empty()) return;
    std::vector<int32_t> moved(new_count, -1);
    for (size_t v = 0; v < remap.size() && v < source_of_vertex.size(); ++v)
      if (remap[v] >= 0) moved[size_t(remap[v])] = source_of_vertex[v];
    source_of_vertex = std::move(moved);
  }
};

// ---- prepare_surface_repair.cpp

/// Phase 2: safe repairs (degenerate and duplicate triangles), then with
/// {repair} auto the surface re-made where it crosses itself, damaged ends
/// trimmed and non-manifold edges split; outward orientation; specks
/// dropped; holes found (and closed with {repair} auto); non-manifold
/// vertices split.
Status repair(PreparedSurface& s, Work& w, const PrepareOptions& options);

// ---- prepare_surface_openings.cpp

/// Whether phase 5 looks for caps on this surface.
bool caps_wanted(const PreparedSurface& s, const Work& w, const PrepareOptions& options);
/// The caps of the current surface; `normals`: triangle_normals(s.mesh) if
/// known.
CapRecognition find_caps(const PreparedSurface& s, const Work& w, const PrepareOptions& options,
                         const TriangleNormals* normals);
/// Phase 5: caps removed, their rims openings of source "cap". `found`:
/// the caps already recognised on the current surface, if any; `normals`:
/// the current surface's, if known.
void open_caps(PreparedSurface& s, Work& w, const PrepareOptions& options,
               std::optional<CapRecognition> found, const TriangleNormals* normals);
/// Phase 6: cuts by the planes and at the points given, then at the blind
/// vessel ends left ({clip} auto).
Status clip(PreparedSurface& s, Work& w, const PrepareOptions& options);
/// A cut by clipping ({clip} auto, {clip_plane}, {clip_at}): an opening of
/// source "clip", listed in s.clips.
Status clip_one(PreparedSurface& s, Work& w, const ClipPlane& plane, OpeningSource::Shape why);
/// Phase 7: flow extensions at the openings asked for.
Status extend_openings(PreparedSurface& s, Work& w, const PrepareOptions& options);

}  // namespace prepare_surface_detail
}  // namespace vm
