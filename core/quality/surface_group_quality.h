// gamma_k (seed section 3) of the surfaces as they are written: per physical
// surface group of the assembled volume mesh, after boundary recovery and
// layer assembly, so that the quality reported is the file's. A cap group
// holds the cap's disc (the core's planar triangulation) and, with layers,
// the ring of split layer faces around it, which is flat by construction:
// the two are summarised apart.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/mesh/volume_mesh.h"
#include "core/quality/triangle_quality.h"

namespace vm {

/// One surface group's triangles as written.
struct SurfaceGroupQuality {
  std::string name;
  int32_t tag = 0;       ///< the mesh's triangle tag
  QualityStats quality;  ///< of the triangles outside the rings
  QualityStats ring;     ///< of the ring triangles (count 0: none)
};

/// Per used triangle tag of `mesh` (names[tag] non-empty), in tag order:
/// the gamma_k of its triangles, those with index in [ring_first,
/// ring_end) summarised in `ring`. Quads are not counted. Precondition:
/// every triangle tag indexes `names`; bins >= 1.
std::vector<SurfaceGroupQuality> surface_group_quality(const VolumeMesh& mesh,
                                                       const std::vector<std::string>& names,
                                                       size_t ring_first, size_t ring_end,
                                                       int bins = 20);

}  // namespace vm
