// A vessel end damaged where the segmentation met the image border (folded
// and overlapping triangles, flaps through the wall, tiny loops, a twist
// that makes the surface non-orientable) is trimmed back to its first clean
// cross-section: the vessel is cut there perpendicular to its axis, as a
// user would cut it by hand.
//
// Method (our own; the axis estimate is the normal-based one of
// core/prepare/cut_across_vessel.h): (1) the damage: triangles that cross
// others (core/mesh/self_intersection.h), lie on non-manifold edges,
// contradict the orientation their neighbours give them (found by
// propagating an orientation from the triangle farthest from any boundary),
// or border loops far smaller than the openings (tiny loops); (2) each
// opening (a boundary loop at least a quarter of the largest's radius)
// with damage within two of its radii is a damaged end: its axis is the
// loop's normal, corrected by the normals of the clean wall behind the
// damage (a tube's normals are perpendicular to its axis); (3) the cut lies
// a margin deeper than the deepest damage along that axis; (4) every
// triangle connected to the end and lying wholly beyond a plane half the
// margin short of the cut is removed, so what is left there is clean, and
// the exact planar cut (core/prepare/clip_surface.h) is made later, once
// the surface is oriented, with the plane returned here. An end whose
// damage reaches deeper than `max_depth` radii is left (the surface is
// then refused as before, saying where).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/geom/vec3.h"
#include "core/mesh/surface_mesh.h"
#include "core/prepare/clip_surface.h"

namespace vm {

struct TrimOptions {
  /// The deepest cut, in radii of the opening.
  double max_depth = 3;
  /// The cut lies this much deeper than the damage: the larger of this
  /// many radii and `margin_edges` local edge lengths.
  double margin_radii = 0.2;
  double margin_edges = 4;
  /// A loop is tiny (damage, not an opening) below this fraction of the
  /// largest loop's radius.
  double tiny_fraction = 0.25;
  /// An end is not trimmed when that would remove more than this fraction
  /// of the surface's triangles (what it would cut is no vessel end).
  double max_removed_fraction = 0.2;
};

/// One damaged end and its cut.
struct TrimmedEnd {
  Vec3 where{};       ///< the opening's centroid, before
  double radius = 0;  ///< the opening's equivalent radius, before
  /// The clean cross-section: through a point on the end's axis, normal
  /// out of the vessel (the side to remove).
  ClipPlane plane;
  double depth = 0;  ///< of the cut in from the opening's centroid, model units
  size_t triangles_removed = 0;
  /// What was wrong there (counts of triangles).
  size_t crossing = 0, nonmanifold = 0, misoriented = 0, tiny_loops = 0;
  /// False: left as it was, the damage reaching too deep (`max_depth`) or
  /// the trim taking too much (`max_removed_fraction`).
  bool trimmed = false;
};

/// Finds the damaged ends of `mesh` and removes the damaged part of each
/// (see the file comment); `crossing_pairs` are the pairs of crossing
/// triangles of `mesh` (find_self_intersections' examples, all of them).
/// `labels` (one per triangle; null or empty: none) follow the removals.
/// Preconditions: no triangle with a repeated vertex; any orientation,
/// non-manifold edges allowed. Returns the ends found, with the plane of
/// each clean cross-section for the cut that finishes the trim.
std::vector<TrimmedEnd> trim_damaged_ends(SurfaceMesh& mesh, std::vector<int32_t>* labels,
                                          const std::vector<std::array<int32_t, 2>>& crossing_pairs,
                                          const TrimOptions& options = {});

}  // namespace vm
