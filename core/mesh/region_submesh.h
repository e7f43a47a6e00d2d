// The part of a volume mesh made of some of its regions, as a mesh of its
// own: the cells of those regions, the boundary faces (triangles, quads)
// that bound one of them, each oriented out of that part, and only the
// points they use. For a fluid-structure case (svFSI) the lumen and the
// vessel wall become two meshes whose interface faces are the same
// triangles on the same coordinates.
#pragma once

#include <cstdint>
#include <vector>

#include "core/mesh/volume_mesh.h"

namespace vm {

/// The submesh of the cells whose region is in `regions` (tet_region,
/// prism_region values). Faces of `mesh` (triangles, quads, with their
/// tags) that are a face of a kept cell are kept, flipped where needed so
/// that each points out of the kept cell; points are renumbered in their
/// original order. Preconditions: mesh's cells and faces index its points.
VolumeMesh region_submesh(const VolumeMesh& mesh, const std::vector<int32_t>& regions);

}  // namespace vm
