// Where a surface crosses itself (overlapping shells, a patch stored twice
// and glued over the wall, two vessels that touch and pass into each
// other, a wall pushed through the opposite one), the part of the surface
// in a box around the crossing is replaced by the boundary of the union of
// what the surface encloses there, so the result bounds one volume.
//
// Method (our own composition of published parts): (1) the crossing
// triangles (core/mesh/self_intersection.h) grouped into places, each in a
// box with a margin of clean surface; (2) on a grid over the box, a signed
// distance whose magnitude is the distance to the surface and whose sign is
// the generalized winding number's (inside where w >= 1/2: Jacobson et al.
// 2013, core/mesh/winding_number.h), so the zero level set is the union's
// boundary, sheets inside the union leaving no trace; (3) marching cubes
// (core/mesh/marching_cubes.h) extracts it, open where it meets the box;
// (4) the surface's triangles that touch the box are removed and each loop
// they leave is sewn to the loop of the new piece nearest it by an optimal
// strip (core/mesh/bridge_loops.h); (5) the place is resolved when the new
// triangles cross nothing and every new edge has two triangles; else the
// box grows and (2)-(5) run again, a few times, before the place is left as
// it was. A box never holds an opening of the surface: a crossing there is a
// damaged vessel end, for the trimming (core/prepare/trim_damaged_ends.h).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/geom/vec3.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

struct ResurfaceOptions {
  /// The grid's spacing in median edge lengths of the surface in the box
  /// (the input's own resolution), unless the box would need more than
  /// `max_cells` cells along an axis.
  double voxel_edges = 1.0;
  int max_cells = 96;
  /// The box around a place's crossing triangles, grown by this many
  /// voxels (at least) on each side at the first try, then doubled.
  double margin_voxels = 4;
  int tries = 3;
  /// A boundary loop whose equivalent radius is above this many voxels may
  /// not lie in a box (an opening: the union is not defined across it).
  double max_hole_voxels = 2;
};

/// What was done at one place.
struct ResurfacedPlace {
  Vec3 where{};               ///< a point of the crossing (model units)
  size_t pairs = 0;           ///< crossing pairs of triangles found there
  Vec3 box_min{}, box_max{};  ///< the box replaced (the last one tried)
  double voxel = 0;
  size_t triangles_removed = 0, triangles_added = 0;
  bool resolved = false;
  /// Why not (an opening in the box, loops that do not pair, crossings left).
  std::string why;
  bool near_opening = false;  ///< not tried: an opening lies in the box
};

struct ResurfaceReport {
  size_t pairs = 0;  ///< crossing pairs before
  std::vector<ResurfacedPlace> places;
  /// The pairs of crossing triangles left (indices into the mesh returned;
  /// up to 4M of them), for the trimming of damaged ends.
  std::vector<std::array<int32_t, 2>> left;
  size_t resolved() const;
};

/// Finds the places where `mesh` crosses itself and replaces the surface
/// around each by the boundary of the union (see the file comment).
/// `labels` (one per triangle; null or empty: none) follow: a new triangle takes the
/// label of the removed triangle nearest it. Preconditions: no triangle
/// with a repeated vertex, no degenerate triangle; the orientation is the
/// file's, consistent per shell (all inward is fine: the sign is taken from
/// the enclosed volume); non-manifold edges and duplicate or crossing
/// triangles are fine. A place whose box would hold an opening is reported
/// `near_opening` and left. Unresolved places are left as they were.
ResurfaceReport resurface_crossings(SurfaceMesh& mesh, std::vector<int32_t>* labels,
                                    const ResurfaceOptions& options = {});

}  // namespace vm
