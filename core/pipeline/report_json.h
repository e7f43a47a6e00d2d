// JSON views of pipeline results, shared by the CLI (--json) and the
// WebAssembly API so that both speak the same keys.
#pragma once

#include <string>

#include "core/pipeline/mesh_job.h"
#include "core/pipeline/prepare_surface.h"

namespace vm {

/// Keys: vertices, triangles, input_triangles, format ("binary"|"ascii"),
/// bounding_box {min, max, diagonal}, components, openings [{perimeter,
/// radius, centroid, normal, vertices}], closed, genus (null if undefined),
/// euler_characteristic, boundary_edges, nonmanifold_edges,
/// nonmanifold_vertices, repairs {...}, quality {min, mean, max, histogram},
/// warnings [..].
std::string analysis_json(const PreparedSurface& surface);

/// Keys: input (analysis_json), output {vertices, triangles, quality,
/// groups [...]}, warnings, seconds.
std::string mesh_report_json(const MeshJobResult& result);

}  // namespace vm
