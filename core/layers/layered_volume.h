// Assembly of the lumen and vessel-wall volumes from the boundary layers and
// the tetrahedral core (Marchandise et al., section 2.2: "those boundary
// layer meshes can be built by extruding outward and inward the lumen
// surface. Next a three-dimensional Delaunay mesh generator is called to
// fill the remaining of the lumen volume with isotropic tetrahedra").
#pragma once

#include <string>
#include <vector>

#include "core/layers/layer_mesh.h"
#include "core/mesh/volume_mesh.h"
#include "core/surface/cap_openings.h"
#include "core/util/result.h"
#include "core/volume/boundary_recovery.h"

namespace vm {

/// Region tags of the assembled mesh (VolumeMesh::tet_region).
inline constexpr int32_t kRegionLumen = 0;
inline constexpr int32_t kRegionBoundaryLayer = 1;  ///< only when tagged apart
inline constexpr int32_t kRegionVesselWall = 2;

/// The assembled volume: mesh.triangle_tag indexes surface_names, and
/// mesh.tet_region region_names (by the constants above; unused names are
/// empty).
struct LayeredVolume {
  VolumeMesh mesh;
  std::vector<std::string> surface_names;
  std::vector<std::string> region_names;
  size_t front_steiner_points = 0;  ///< recovery's points on the layer front, absorbed
  /// Of those, the ones the viscous layer's top slice took (the wall keeps
  /// its triangles, absorb_front_points.h).
  size_t absorbed_steiner_points = 0;
  /// Recovery's points that became wall vertices (splitting its triangles):
  /// carried down the layers' columns, or on a wall with no viscous layer.
  size_t wall_steiner_points = 0;
  /// Of those, the ones slid along their wall edge to better the wall's
  /// triangles around them (slide_wall_points.h).
  size_t reoptimized_steiner_points = 0;
  /// Where those points are in the mesh: 3 doubles each.
  std::vector<double> wall_steiner_places;
  /// The core's tetrahedra in mesh.tets: [core_first, core_first + core_count).
  size_t core_first = 0, core_count = 0;
  /// The layers' rings at the openings in mesh.triangles (split prisms'
  /// faces, flat by construction): [ring_first, ring_end); empty when the
  /// rings are quads (keep_prisms) or there are no layers.
  size_t ring_first = 0, ring_end = 0;
};

/// Merges, into one conforming mesh:
/// - `inner` (optional): the viscous layer grown inward from the wall;
/// - `outer` (optional): the vessel wall grown outward from the same wall
///   (its wall points equal inner's, as extrude_layers guarantees);
/// - the core: `caps` (the core's boundary capped: inner's front when there
///   is an inner layer, else the wall), `recovered` (its boundary recovery:
///   triangles with their cap tags and parents), and `core` (the recovered
///   region filled: points = recovered's points then new ones, tets).
/// Front triangles split by Steiner points of the recovery are absorbed in
/// the viscous layer's top slice (absorb_front_points) when its tetrahedra
/// there are valid and the prisms are split; else they, and wall triangles
/// split on a wall with no viscous layer, are propagated through the
/// layers' columns (refine_layer_columns), and those on a wall edge slide
/// along it to better the wall (slide_wall_points). Wall edges the recovery
/// flipped (recovered.input_triangles, wall_flip_rule) flip in the layers'
/// columns. Surfaces:
/// `wall` (tag 0; the lumen/vessel-wall interface when there is a vessel
/// wall), each cap's name (the core's cap plus the viscous layer's ring
/// there), `outer_wall`, and `wall_<cap>` (the vessel wall's ring at each
/// opening). Regions: lumen (core + viscous layer), boundary_layer (the
/// viscous layer alone, when tag_layer), vessel_wall. Prisms are split into
/// tetrahedra by the smallest-index rule, or kept (keep_prisms: mesh.prisms,
/// and the rings as quads in mesh.quads).
/// Precondition: `recovered` recovered `caps` (its input triangles are
/// caps.mesh's, the wall's first, up to the flips it made).
/// Errors: those of refine_layer_columns, a layer opening without its cap.
Result<LayeredVolume> assemble_layered_volume(const LayerMesh* inner, const LayerMesh* outer,
                                              const CappedSurface& caps,
                                              const RecoveredVolume& recovered,
                                              const VolumeMesh& core, bool tag_layer,
                                              bool keep_prisms = false);

}  // namespace vm
