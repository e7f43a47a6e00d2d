// Pieces the caller assembles a layered volume from (docs/
// ARCHITECTURE.md, stages 4 and 7; Marchandise et al., section 2.2: the
// prisms are split into tetrahedra, the remaining lumen is filled with
// tetrahedra bounded by the front and the caps).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/layers/layer_mesh.h"
#include "core/mesh/surface_mesh.h"
#include "core/mesh/volume_mesh.h"

namespace vm {

/// The faces of opening `o`'s layer prisms that lie in its cap plane:
/// per rim edge (rim[i], rim[i + 1]) and layer slice k, the quad of the two
/// columns between layers k and k + 1, split into two triangles by the
/// diagonal from its smallest vertex id (as split_prism cuts it, so the
/// triangles are faces of the split prisms). 3 ids per triangle,
/// 2 N per rim edge, oriented along the plane's normal (out of the lumen,
/// which is outward of the layer region both for the viscous layer and for
/// the vessel wall). Inward layers: they and the cap of the front's rim
/// form `inlet` / `outlet_k`; outward: `wall_inlet` / `wall_outlet_k`.
/// Precondition: o < m.openings.size().
std::vector<int32_t> ring_triangles(const LayerMesh& m, size_t o);

/// The same faces unsplit, 4 ids per quad in the same orientation (for
/// meshes that keep the prisms).
std::vector<int32_t> ring_quads(const LayerMesh& m, size_t o);

/// ring_quads over explicit columns: `columns` holds (layers + 1) ids per
/// rim vertex in rim order (as LayerOpening::columns), the rim running
/// clockwise around the plane normal; 4 ids per quad, oriented along the
/// normal for columns going inward of the rim (outward = false) or outward.
std::vector<int32_t> ring_quads_of_columns(const std::vector<int32_t>& columns, int layers,
                                           bool outward);

/// Each quad (4 ids, a cycle) as two triangles cut by the diagonal from
/// its smallest id, keeping the cycle's orientation: 6 ids per quad.
std::vector<int32_t> split_quads(const std::vector<int32_t>& quads);

/// The three tetrahedra of every prism (6 ids each, VolumeMesh order) by
/// split_prism's smallest-index rule: 12 ids per prism. The split depends
/// only on the order of the ids, so it is unchanged by any increasing
/// renumbering of the points (e.g. when the caller merges several meshes).
std::vector<int32_t> prisms_to_tets(const std::vector<int32_t>& prisms);

/// The front as a compact surface with the wall's numbering: vertex v is
/// the last layer's point above wall vertex v (LayerMesh id
/// m.layer_vertex(v, m.layers)), triangles and orientation the wall's. Its
/// openings are the wall's rims (same vertex ids, same loop order), planar.
SurfaceMesh front_surface(const LayerMesh& m);

/// The layer region alone as a volume mesh, for checks and inspection:
/// m's points; its prisms split into tetrahedra (split = true) or kept;
/// region 0; boundary triangles oriented outward of the region: the wall
/// (tag 0), the front (tag 1), the rings of opening o (tag 2 + o, split
/// only, since check_volume_mesh matches triangles).
VolumeMesh layer_volume(const LayerMesh& m, bool split);

}  // namespace vm
