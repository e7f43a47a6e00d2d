// Boundary recovery: the tetrahedralization of the region bounded by a
// closed triangulated surface, in which every surface triangle is a union of
// faces of the mesh (docs/ARCHITECTURE.md, stage 6, before refinement).
//
// Method (after George, Hecht and Saltel, "Automatic mesh generator with
// specified boundary", CMAME 92, 1991, and Si, "TetGen, a Delaunay-based
// quality tetrahedral mesh generator", ACM TOMS 41, 2015): Delaunay
// tetrahedralization of the surface vertices (core/volume/delaunay3d.h);
// missing edges, then missing faces, recovered by flips (2-3, 3-2/edge
// removal; before a Steiner point, along the whole missing edge, and an edge
// of a crossed face removed where the face's own flip is invalid); what
// flips cannot recover is flipped on the surface where the caller allows it,
// else split by Steiner points on the
// surface edges (midpoints, or concentric shells around input vertices), the
// surface triangles being split with them so the surface stays conforming;
// then the tetrahedra outside are removed by a flood fill from the convex
// hull that stops at the surface.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/mesh/volume_mesh.h"
#include "core/util/result.h"
#include "core/volume/delaunay3d.h"

namespace vm {

struct RecoveryOptions {
  /// Upper bound on Steiner points; -1: one per input triangle + 1000.
  int64_t max_steiner_points = -1;
  /// Flips tried per missing edge or face before a Steiner point.
  int max_flips_per_item = 32;
  /// When false, only Steiner points are used (conforming Delaunay).
  bool use_flips = true;
  /// When set, a missing surface edge (a, b) that flips cannot recover,
  /// between two whole input triangles (a, b, c) and (b, a, d) of the same
  /// tag, is flipped on the surface to (c, d) instead of split by a Steiner
  /// point, if may_flip_surface(a, b, c, d, tag) says the surface may
  /// change so (its shape and quality there are the caller's to judge).
  /// Never an edge a surface flip made, and only with flips (use_flips).
  std::function<bool(int32_t a, int32_t b, int32_t c, int32_t d, int32_t tag)> may_flip_surface;
};

/// Region tags the kernel carries after recovery (Delaunay3D::tag).
constexpr int32_t kOutsideTag = 0;
constexpr int32_t kInsideTag = 1;

struct RecoveredVolume {
  /// points: the input points (same order), then the Steiner points.
  /// tets: the positive tetrahedra inside the surface (tet_region 0).
  /// triangles: the surface as split by Steiner points, oriented outward
  /// like the input; triangle_tag: the tag of the input triangle each came
  /// from. Prisms empty.
  VolumeMesh mesh;
  /// Per output triangle: the index of the input triangle it came from, in
  /// input_triangles.
  std::vector<int32_t> triangle_parent;
  /// The input triangles after the surface flips (may_flip_surface): 3 ids
  /// each, same count and order as the input, equal to it but for the
  /// flipped pairs; the output triangles tile them.
  std::vector<int32_t> input_triangles;
  /// Surface edges flipped instead of a Steiner point: their count, and
  /// the new edges (2 point ids each).
  int64_t surface_flips = 0;
  std::vector<int32_t> flipped_edges;
  int64_t steiner_points = 0;
  /// Missing edges the first flips left that flips along the whole
  /// segment then recovered (each would have been a Steiner point).
  int64_t edges_recovered_along = 0;
  int64_t flips = 0;
  /// Whether the conforming-Delaunay fallback (Steiner points only) was
  /// needed after flips and Steiner points stalled.
  bool used_fallback = false;
  /// Why the first attempt stalled (empty unless used_fallback).
  std::string fallback_reason;
  /// The working triangulation, for refinement: every output triangle is a
  /// constrained face; tag() is kInsideTag inside, kOutsideTag outside.
  /// Insert more points with insert(p, hint, /*respect_constraints=*/true).
  Delaunay3D kernel;
};

/// Recovers the surface (points: 3 doubles per vertex; triangles: 3 vertex
/// indices per face, counterclockwise seen from outside; tags: one per
/// triangle) in the Delaunay tetrahedralization of the points.
/// Preconditions, checked (errors as values): one closed, manifold,
/// consistently and outward oriented surface without self-intersections
/// (the last is not checked; a self-intersecting surface fails to recover);
/// no two vertices at the same position; no degenerate triangle. Points
/// not used by any triangle are kept as vertices if they lie inside.
Result<RecoveredVolume> recover_boundary(const std::vector<double>& points,
                                         const std::vector<int32_t>& triangles,
                                         const std::vector<int32_t>& tags,
                                         const RecoveryOptions& options = {});

}  // namespace vm
