// Flow extensions: straight tubes added at the openings so that the flow
// develops before it reaches the region of interest, as VMTK's
// vmtkflowextensions does (Antiga et al., "An image-based modeling framework
// for patient-specific computational hemodynamics", Med Biol Eng Comput 46,
// 2008): each opening is extended along its normal by a length in local
// radii, its cross-section blending from the opening's shape to a circle of
// the same area, joined to the wall with the wall's own direction (a Hermite
// curve per rim vertex), then straight to a planar circular end.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/mesh/topology.h"
#include "core/util/result.h"

namespace vm {

/// What was added at one opening.
struct FlowExtension {
  size_t opening = 0;           ///< index into the openings given
  double length = 0;            ///< model units (radii x the opening's radius)
  size_t rings = 0;             ///< rings of vertices added
  std::array<double, 3> end{};  ///< centre of the new, circular opening
};

/// Extends `mesh` at openings[i] by lengths[i] times that opening's
/// equivalent radius along its outward normal (0: no extension). The new
/// triangles are appended (their labels, when `labels` holds one per
/// triangle, are those of the wall triangle they continue); new vertices
/// are appended. For each new vertex, `new_vertex_opening` gets the index
/// of the opening it extends (so callers can carry what they know about an
/// opening to its new rim). The new end of each extension is a planar
/// circle of the opening's area, perpendicular to its normal.
///
/// Preconditions: `mesh` manifold and outward oriented; `openings` its
/// boundary loops (analyze_topology); lengths.size() == openings.size().
/// Errors (with the opening's number and place): an opening whose rim
/// folds back onto its axis; an extension that runs into the wall (the
/// message names the point and asks for a shorter length).
Result<std::vector<FlowExtension>> add_flow_extensions(SurfaceMesh& mesh,
                                                       std::vector<int32_t>* labels,
                                                       const std::vector<Opening>& openings,
                                                       const std::vector<double>& lengths,
                                                       std::vector<int32_t>* new_vertex_opening);

}  // namespace vm
