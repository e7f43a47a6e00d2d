// A cut across a vessel at a place the user points to: the plane through
// that place perpendicular to the local vessel axis, facing the smaller side.
//
// Method (our own; the axis estimate is the classical one for tubes: a
// tube's normals are perpendicular to its axis, so the axis is the direction
// least represented among the normals, the eigenvector of the smallest
// eigenvalue of sum(A_i n_i n_i^T), as in normal-based centerline and
// cylinder fitting, e.g. Kumar et al., "Automatic extraction of cylinder
// axes", 2009): (1) the surface vertex nearest the point given; (2) the
// normals of the connected surface within a ball around it give the axis;
// the ball grows until the normals spread round the vessel; (3) the plane
// section through the vertex perpendicular to that axis gives the vessel's
// centre and radius R (the loop through the vertex, core/mesh/level_loops.h);
// (4) rounds of (2)-(3) with the ball centred on the section's centroid, of
// radius 1.5 R, until the axis settles; (5) the side removed is the one
// with less surface (both cuts are tried with core/prepare/clip_surface.h).
// (6) Where the vessel is no tube because the point lies on a vessel's end,
// the cut is that end's: at the rim of a fan or a dome cap
// (core/prepare/recognize_caps.h) when the point lies on it or within half
// a radius of its rim, else the one {clip} auto makes at a rounded, flat or
// short root's end (core/prepare/vessel_ends.h) when the point lies beyond
// one radius behind it; within 1.5 radii of the end's axis.
#pragma once

#include <array>

#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"
#include "core/prepare/clip_surface.h"
#include "core/util/result.h"

namespace vm {

/// A cut across a vessel.
struct VesselCut {
  /// Through the centroid of the vessel's section, perpendicular to the
  /// local axis, the normal toward the side with less surface (the side a
  /// clip removes).
  ClipPlane plane;
  double radius = 0;        ///< equivalent radius sqrt(area / pi) of the section
  double roundness = 0;     ///< smallest / largest distance of the section from its centroid
  double area_removed = 0;  ///< area of the smaller side (model units squared)
};

/// The cut across the vessel at the surface point nearest `near` (model
/// coordinates), or, on a vessel's end, that end's cut (step 6).
/// Preconditions: edge-manifold, consistently oriented, no degenerate
/// triangle; `adj` is build_adjacency(mesh). Errors (kBadInput, saying
/// where): an empty surface; a place, not on a vessel's end, where the
/// section is not one closed loop round enough to be a vessel's (a
/// branching, an aneurysm, a flat region); a section that does not split
/// the surface in two. O(surface) per round, a few rounds; step 6 finds
/// the vessel ends (O(n log n)).
Result<VesselCut> cut_across_vessel(const SurfaceMesh& mesh, const TriangleAdjacency& adj,
                                    const std::array<double, 3>& near);

}  // namespace vm
