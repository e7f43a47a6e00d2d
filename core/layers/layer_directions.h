// Extrusion directions of the boundary layer (Marchandise et al., section
// 2.2: "from each surface node a direction is picked ... an estimate of the
// surface normal at the node using Gouraud shading"; the advancing-layer
// method of Pirzadeh 1996 / Garimella and Shephard 2000 / Aubry and Lohner
// 2009 for smoothing and visibility).
#pragma once

#include <cstdint>
#include <vector>

#include "core/layers/layer_geometry.h"
#include "core/layers/layer_mesh.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"
#include "core/util/result.h"

namespace vm {

/// Per-vertex directions and the normals they were built from.
struct LayerDirections {
  /// 3 per wall vertex: the angle-weighted (Gouraud) vertex normal, unit,
  /// on the layer side (into the lumen for inward layers, out of it for
  /// outward ones).
  std::vector<double> normal;
  /// 3 per wall vertex: the unit extrusion direction.
  std::vector<double> direction;
  /// 3 per wall triangle: its unit normal on the layer side.
  std::vector<double> triangle_normal;
  /// Per wall vertex: the opening whose rim it is on, or -1.
  std::vector<int32_t> opening_of;
  /// Smallest direction . triangle normal over every triangle corner.
  double min_visibility = 1;
};

/// Directions in phases: (1) angle-weighted vertex normals; (2) rim
/// vertices: the normal projected into the opening's plane, falling back on
/// the rim polygon's in-plane normal when the projection is short or turns
/// away from it, pointing into the cap for inward layers and away from it
/// for outward ones; (3) `passes` Jacobi passes of Laplacian smoothing on the
/// unit sphere (d <- normalize(d + normalize(mean of the 1-ring))) with the
/// rim directions held; (4) plane guard: a vertex near an opening whose
/// column of length reach[v] would end closer to the cap plane than half
/// its own distance to it (or beyond it) is tilted away from the plane just
/// enough, so the front never crosses the cap planes and the rings stay the
/// only layer faces in them; (5) visibility: every direction is pushed
/// toward the normal of the incident triangle it sees worst until it sees
/// all of them at direction . normal >= 0.4 (rim directions kept in their
/// plane), or the best found is kept.
///
/// Inputs: `wall` manifold and outward oriented, rim vertices already on
/// their planes; `adj` and `rings` built on it; `openings` with plane frames
/// and rims filled (columns unused); `reach` the requested thickness per
/// vertex (model units; empty: no plane guard). Errors: a vertex no direction can see
/// its triangles from (direction . normal < 0.02 at some corner, e.g. a
/// needle spike), a rim vertex whose wall meets the cap plane tangentially.
Result<LayerDirections> layer_directions(const SurfaceMesh& wall, const TriangleAdjacency& adj,
                                         const layers::VertexRings& rings,
                                         const std::vector<LayerOpening>& openings, bool outward,
                                         int passes, const std::vector<double>& reach);

}  // namespace vm
