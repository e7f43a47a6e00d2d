// Clipping a closed vessel surface open: at its vessel ends, or by planes the
// user gives, each cut becoming a planar opening.
//
// Method (our own description; the idea is VMTK's end clipping, Antiga et
// al., "An image-based modeling framework for patient-specific computational
// hemodynamics", Med. Biol. Eng. Comput. 46, 2008: a plane across the vessel
// near its end, keeping the part connected to the rest): for each plane,
// (1) vertices within a small fraction of their shortest edge from the plane
// are moved onto it (unless that would turn a triangle over), so the cut
// makes no slivers; (2) the surface's section by the plane is traced as
// level curves of the signed distance (core/mesh/level_loops.h) and the
// closed loop around the plane's point is chosen: the innermost one that
// encloses the point, else the nearest one within reach; (3) the loop must
// separate the surface: the side its normal points to, grown from the loop
// over the surface without crossing it (not limited to the half-space: a
// vessel end that bends back is removed whole; other vessels crossing the
// plane elsewhere are not touched), is removed; (4) the triangles the loop
// crosses are split at new vertices on the plane, so the opening is an
// exactly planar loop. A vertex on the plane that the loop would meet twice
// (the surface touching the plane there from two sides) is left off the
// plane (moved back by a small fraction of its shortest edge if it lay
// exactly on it), so the opening never pinches. After all planes, the
// largest component (by area) is kept.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/util/result.h"

namespace vm {

/// A cutting plane: a point on it and the unit normal pointing to the side
/// that is removed (out of the part kept).
struct ClipPlane {
  std::array<double, 3> point{};
  std::array<double, 3> normal{};
};

struct ClipOptions {
  /// A vertex closer to the plane than this fraction of its shortest edge
  /// is moved onto the plane.
  double snap_fraction = 0.05;
  /// When no loop of the section encloses the plane's point, the nearest one
  /// is cut if it passes within this many of its own radii of the point.
  double reach = 1.0;
  /// A cut may remove at most this fraction of the surface's area.
  double max_removed_fraction = 0.5;
};

/// What one plane cut.
struct ClipCut {
  ClipPlane plane;                   ///< as given (normal made unit)
  std::array<double, 3> centroid{};  ///< of the new opening's loop
  double radius = 0;                 ///< sqrt(area / pi) of the loop
  double perimeter = 0;
  size_t loop_vertices = 0;
  double area_removed = 0;  ///< model units squared
  size_t triangles_removed = 0;
};

struct ClipResult {
  SurfaceMesh mesh;
  /// One label per triangle of `mesh` (a split triangle's pieces keep its
  /// label); empty when no labels were given.
  std::vector<int32_t> labels;
  /// Per vertex of `mesh`: the index of the plane whose cut loop it lies on
  /// (new vertices and vertices moved onto the plane), or -1.
  std::vector<int32_t> cut_of_vertex;
  /// Per vertex of `mesh`: the input vertex it is, or -1 for a new vertex.
  std::vector<int32_t> input_vertex;
  std::vector<ClipCut> cuts;  ///< one per plane, in order
  /// Pieces left disconnected from the largest component, removed.
  int components_dropped = 0;
  size_t triangles_dropped = 0;
  double area_dropped = 0;
};

/// Cuts `mesh` with each plane in turn (on the result of the previous cuts).
/// Preconditions: edge-manifold where the planes cut, consistently oriented
/// (outward), no degenerate triangle; `labels` has one entry per triangle or
/// is empty. Each plane removes the part of the surface beyond the section
/// loop around its point (see the file comment) and leaves an exactly planar
/// boundary loop: the new vertices lie on the plane up to rounding (they are
/// interpolated along the crossed edges), vertices moved onto it exactly up
/// to rounding too; no triangle of zero area is made; orientation is kept.
/// Errors (kBadInput, with the plane's point and the model's coordinates): a
/// plane that does not cut the surface, or not within reach of its point; a
/// section loop that runs into an opening of the surface; a loop that does
/// not separate the surface (a handle); a cut that would remove more than
/// max_removed_fraction of the surface.
Result<ClipResult> clip_surface(const SurfaceMesh& mesh, std::span<const int32_t> labels,
                                std::span<const ClipPlane> planes, const ClipOptions& options = {});

}  // namespace vm
