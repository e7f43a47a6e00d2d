// Fidelity of a remeshed surface to its input: input vertices farther than
// a fraction of h from the output (segmentation bumps and ridges sharper
// than h can follow) get an output vertex moved onto them and pinned there.
// Marchandise et al., section 2.1 ask every new vertex to lie on the input;
// this adds the converse, the input lying near the new surface.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/mesh/triangle_bvh.h"
#include "core/surface/optimize_surface.h"

namespace vm {

struct PinStats {
  size_t far = 0;     ///< input vertices beyond the limit (not skipped)
  size_t pinned = 0;  ///< output vertices put onto them (moved or new)
};

/// For each input vertex v with gaps[v] > limit * h[v], largest relative
/// gap first, and not flagged in `skip` (empty, or one flag per input
/// vertex): the output triangle closest to v gets a vertex exactly at v,
/// with (in `wall`) home = a triangle of v, fixed = kPinned and pin_of =
/// v. Its
/// nearest corner moves there if it is free (kFree), closer than 0.35 h[v],
/// and its triangles keep gamma_k >= 0.3; else the edge nearest to v's
/// projection (barycentric < 0.2; not an opening or crease edge) or the
/// triangle is split at v (new triangles appended, with gamma_k >= 0.1;
/// new vertex appended to the points and wall.home, fixed and pin_of, not
/// to wall.size: the caller sizes the new vertices). Every changed
/// triangle turns by less than 60 degrees.
/// Triangles changed once are not changed again in the same call.
/// `output` is manifold and oriented like `input`; wall.home, fixed and
/// pin_of: one per output vertex; h, gaps: one per input vertex, h > 0
/// (gaps: distances_to_surface(output, input.points)). bvh: a tree of
/// `output` as it is (build_triangle_bvh), or null to build one.
PinStats pin_to_input(SurfaceMesh& output, WallVertices& wall, const SurfaceMesh& input,
                      const std::vector<double>& h, const std::vector<double>& gaps, double limit,
                      const std::vector<uint8_t>& skip, const TriangleBvh* bvh = nullptr);

/// Frees (wall.fixed = kFree, wall.pin_of = -1) every pinned vertex of a
/// triangle of `output` with gamma_k < min_gamma or with a folded corner
/// (star_visibility < 0.25: about 75 degrees), and flags in `skip` (one per
/// input vertex) the input vertex it was pinned to (wall.pin_of, one per
/// output vertex), so that it is not pinned again. Returns the number freed.
size_t unpin_poor(const SurfaceMesh& output, WallVertices& wall, double min_gamma,
                  std::vector<uint8_t>& skip);

}  // namespace vm
