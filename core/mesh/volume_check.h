// Validity checks of a volume mesh before it is written (docs/
// ARCHITECTURE.md, stage 7: no inverted element, conforming, every boundary face a surface
// triangle, every surface triangle on the boundary or an interface).
#pragma once

#include <cstddef>

#include "core/mesh/volume_mesh.h"
#include "core/util/result.h"

namespace vm {

struct VolumeCheck {
  size_t boundary_faces = 0;  ///< element faces used once (the domain's boundary)
  double volume = 0;          ///< total volume of the elements (model units cubed)
  double min_volume6 = 0;     ///< smallest tet_volume6 over all (sub-)tetrahedra
};

/// Checks `m` (tetrahedra and prisms, each prism as its three
/// sub-tetrahedra by the smallest-index diagonal rule): every element
/// strictly positive (exact orient3d); every face shared by at most two elements, with
/// opposite orientations (conforming; prism quads by their vertex set); the
/// faces used once are exactly m.triangles (as vertex sets; each triangle
/// oriented outward of its element, i.e. like the element's face) plus no
/// other; every triangle either on the boundary or between two regions
/// (an interface). Errors name the first violation and where.
Result<VolumeCheck> check_volume_mesh(const VolumeMesh& m);

/// The cheap part of check_volume_mesh: every element strictly positive
/// (exact orient3d; prisms by their split) and every index in range; fills
/// volume and min_volume6 only.
Result<VolumeCheck> check_volume_orientation(const VolumeMesh& m);

}  // namespace vm
