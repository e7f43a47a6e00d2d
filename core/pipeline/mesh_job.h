// The whole job: STL bytes + options in, MSH text + report out.
// Stages so far: prepare, surface remeshing (conformal maps), write the
// remeshed surface as `wall`; caps, layers and volume plug in here later.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/io/msh_writer.h"
#include "core/pipeline/prepare_surface.h"
#include "core/surface/remesh_surface.h"
#include "core/util/progress.h"
#include "core/util/result.h"

namespace vm {

struct MeshJobOptions {
  PrepareOptions prepare;
  MshVersion msh_version = MshVersion::k41;
  /// Keep only the largest connected component instead of refusing inputs
  /// with several components.
  bool largest_component_only = false;
  /// Remesh the surface (else the repaired input surface is written).
  bool remesh = true;
  RemeshOptions remesh_options;
};

/// How faithful the remeshed surface is to its input (issue 3's checks).
struct SurfaceFidelity {
  /// Largest distance of an output vertex to the input surface, relative to
  /// the input's bounding-box diagonal (0 up to rounding: vertices lie on it).
  double max_vertex_offset = 0;
  /// Largest distance of an input vertex to the output surface, relative to
  /// the target size h at that vertex (how much detail the size discards).
  double max_input_gap = 0;
  /// Input vertices farther than 0.1 h from the output surface.
  size_t input_gap_vertices = 0;
  /// Pairs of output triangles that intersect (0 for a valid surface).
  size_t self_intersections = 0;
};

/// One physical group of the written file and its element count.
struct OutputGroup {
  int dim = 2;
  std::string name;
  size_t elements = 0;
};

struct MeshJobResult {
  std::string msh;                    ///< the MSH file contents
  PreparedSurface surface;            ///< the input as read and analyzed
  SurfaceMesh output_surface;         ///< the surface written (wall)
  std::vector<float> output_quality;  ///< gamma_k per output triangle
  QualityStats output_quality_stats;
  std::vector<OutputGroup> groups;  ///< physical groups written
  bool remeshed = false;
  RemeshStats remesh_stats;        ///< when remeshed
  TopologyReport output_topology;  ///< when remeshed (checked equal to the input's)
  SurfaceFidelity fidelity;        ///< when remeshed
  std::vector<std::string> warnings;
  double seconds_total = 0;
};

Result<MeshJobResult> run_mesh_job(std::span<const uint8_t> stl_bytes,
                                   const MeshJobOptions& options = {},
                                   const ProgressFn& progress = {});

}  // namespace vm
