// The blind vessel ends of a vessel surface (a segmentation with rounded or
// flat ends, closed or open elsewhere) and where to cut each open,
// perpendicular to the vessel.
//
// Method (our own; the placement follows VMTK's end clipping, Antiga et al.,
// Med. Biol. Eng. Comput. 46, 2008: a plane perpendicular to the centerline
// some radii in from the end):
// (1) Candidates: the persistent local maxima (core/mesh/persistent_maxima.h)
//     of the geodesic distance (along edges, core/mesh/edge_geodesics.h)
//     from two far points of each component (the farthest point from any
//     vertex, then the farthest from that one): every vessel tip is a
//     maximum of the distance from a point outside its vessel, with a
//     persistence about its vessel's length beyond the branching; the two
//     seeds cover each other's tips. Noise has small persistence.
// (2) A first axis and radius from the rings of geodesic distance around
//     the candidate (level curves, core/mesh/level_loops.h): their radius
//     grows over the end's cap and levels off on the vessel (the knee gives
//     a first radius R), their centroids follow the vessel (a first axis).
// (3) Refinement by plane sections marched in from the tip every quarter
//     radius: straight along the axis over the cap, then following the
//     section centroids (so a curved vessel is followed; depths are
//     measured along this path; the path turns by at most 6 degrees a
//     step, so it follows bends of radius 2.4 R or more but not the corner
//     from an aneurysm's neck into its parent vessel). The cap ends where
//     full round sections of radius about R begin (at most 3.5 R in); the
//     axis at the end comes from the sections just behind it, R is the
//     median section radius, the tip is the end's farthest point along the
//     axis; a few rounds until they settle (the first ones also fix the
//     scale when the rings' radius was far off).
// (4) Tests that the end is a vessel's end and not a bulge (an aneurysm dome
//     is a geodesic maximum too, with a round section at its equator, but
//     no tube behind it): every section from the cap's end to `tube_length`
//     radii in, and for a radius behind the cut, is one closed round loop
//     around the path of radius about R; the part beyond the cut is a small
//     end (a cap: bounded by the cut loop alone, near the axis, of the area
//     of a cap of its length); the tip's persistence is at least
//     `min_persistence` R.
// (5) The cut: D R in from the tip (D = clip_distance), or deeper where the
//     section there is less round than the tube (it would cross a flat end
//     cut obliquely across the vessel: segmentations cropped by the image
//     have such ends), through the centroid of that section, normal along
//     the axis of the sections behind it, toward the tip.
// (1b) More candidates: the maxima of the geodesic distance from the ends
//     found (a short, wide root, whose end the far points' distance passes
//     by into the branches beside it, is far from every end), except near
//     an extremity that the tests rejected.
// (6) A short root: of the candidates that are no vessel end, the widest
//     (first radius at least 0.7 of the widest end or opening) are tried
//     again with the bounds of a short end: a persistence of 0.35 R, R the
//     widest round section before the branching, a tube within 10% of R
//     from the cap's end to 1.5 R in and half a radius behind the cut. The
//     first that passes, if at least 0.9 times as wide as every vessel end
//     and opening (a root; an aneurysm is narrower than its parent
//     vessel), is an end.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/prepare/clip_surface.h"

namespace vm {

struct VesselEndOptions {
  /// D: the cut lies D local radii in from the tip (the option clip_distance).
  double clip_distance = 1;
  /// A tip's geodesic persistence must be at least this many local radii.
  double min_persistence = 1;
  /// The vessel must be a tube from the end of its cap (about 1 radius in
  /// for a rounded end) to at least this many radii in from the tip, and
  /// for a radius behind the cut.
  double tube_length = 2.5;
  /// Sections in the tube have radii within (1 +- radius_tolerance) R ...
  double radius_tolerance = 0.35;
  /// ... are round: the smallest distance of a loop point from its centroid
  /// is at least this fraction of the largest ...
  double min_roundness = 0.4;
  /// ... and centred: their centroids lie within this many R of the axis.
  double max_offset = 0.5;
};

/// One vessel end and its proposed cut.
struct VesselEnd {
  std::array<double, 3> tip{};   ///< the end's farthest point along the axis
  std::array<double, 3> axis{};  ///< unit, along the vessel toward the tip
  double radius = 0;             ///< R: median section radius 1..tube_length R in (model units)
  /// The cut: cut_depth R in from the tip, perpendicular to the vessel,
  /// through the centroid of that section, normal toward the tip.
  ClipPlane plane;
  double cut_radius = 0;  ///< equivalent radius of that section
  /// The cut's depth in from the tip, in radii: clip_distance, or deeper
  /// where the section there would not be round (it would cross a flat end
  /// cut obliquely across the vessel).
  double cut_depth = 0;
  double persistence = 0;  ///< of the tip's geodesic maximum
  /// A short root (step 6): its tube behind the cut is shorter than
  /// tube_length radii, and it is the widest vessel end.
  bool short_end = false;
};

/// A geodesic extremity that is not taken as a vessel end.
struct NotAVesselEnd {
  std::array<double, 3> where{};  ///< the extremity
  double radius = 0;              ///< its first radius estimate
  std::string why;                ///< e.g. "no tube of radius 0.95 behind it"
};

struct VesselEnds {
  std::vector<VesselEnd> ends;  ///< by decreasing radius
  /// Extremities as prominent as a vessel end (persistence >= 1.5 R) that
  /// were rejected: bulges such as aneurysm domes.
  std::vector<NotAVesselEnd> rejected;
};

/// Finds the blind vessel ends of `mesh`. Preconditions: edge-manifold,
/// consistently outward oriented, no degenerate triangle; closed, or open
/// elsewhere (rings and sections that reach an opening fail the tests, so
/// an opening's rim is never taken for an end, nor an end next to one). A
/// surface without vessel ends (a torus, a sphere) gives none. O(n log n) for the candidates plus, per
/// candidate, work proportional to the surface within a few radii of its tip.
VesselEnds find_vessel_ends(const SurfaceMesh& mesh, const VesselEndOptions& options = {});

}  // namespace vm
