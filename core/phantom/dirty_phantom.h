// Segmentation defects added to a clean phantom, for the tests of the
// repair (prepare phase 2): what real lumen surfaces exported from
// segmentation tools carry.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm {

/// What was added, for tests to compare the analysis against.
struct DirtTruth {
  /// Boundary loops made: 1-ring holes, plus the two 3-edge holes that
  /// touch at one vertex. Each is a simple loop away from the openings and
  /// from the other defects.
  int holes = 0;
  int fins = 0;             ///< fin triangles (each makes a non-manifold edge)
  int bowtie_vertices = 0;  ///< vertices where two holes touch (non-manifold)
  int duplicates = 0;       ///< duplicated triangles (half of them reversed)
  int flipped = 0;          ///< triangles reversed in the flipped patch
  int band_triangles = 0;   ///< zero-area triangles of the band
};

/// Adds to an oriented, manifold phantom `mesh` (deterministically from
/// `seed`; the mesh's median edge length h sets the spacing): `holes` holes
/// (the 1-ring of a vertex removed; 5 to 50), two holes touching at one
/// vertex (two triangles of one vertex star sharing only that vertex), a
/// fin (a triangle on a wall edge, standing out of the wall), 6 duplicated
/// triangles, a flipped patch (a vertex's 2-ring reversed), and a zero-area
/// band (a 1-ring cut loose along its rim and joined back by zero-area
/// triangles to coincident copies of the rim's vertices, which welding
/// merges). Defects sit at vertices at least 6 h apart and 5 h from the
/// openings; on a small mesh fewer holes fit (the truth says how many). The
/// result is not welded: the band's copies coincide with the rim.
DirtTruth add_segmentation_defects(SurfaceMesh& mesh, uint32_t seed, int holes = 12);

/// What add_damaged_ends did, per opening damaged.
struct DamagedEnd {
  std::array<double, 3> center{};  ///< of the opening's loop before the damage
  std::array<double, 3> axis{};    ///< unit, out of the vessel
  double radius = 0;               ///< sqrt(area / pi) of the loop
  /// How far in from the opening's plane the damage reaches (model units).
  double depth = 0;
};

/// Damages every opening of an oriented, manifold phantom with open ends as
/// a vessel cut at an image border is damaged (deterministically from
/// `seed`): a run of rim vertices pushed in along the vessel past the next
/// ring, so that their triangles fold over their neighbours; a flap on a
/// rim edge dipping through the wall; a triangle removed one ring in (a
/// tiny loop beside the opening); and a twisted band joining two rim edges
/// with a half turn, which makes the surface non-orientable. Openings with
/// fewer than 16 rim vertices are left. The result is welded (no new
/// coincident vertices).
std::vector<DamagedEnd> add_damaged_ends(SurfaceMesh& mesh, uint32_t seed);

}  // namespace vm
