// Volume refinement to a size field (docs/ARCHITECTURE.md, stage 6):
// points are inserted inside the tagged region of a constrained Delaunay
// kernel until its edges are no longer than about h(x), the boundary (its
// constrained faces and their vertices) staying exactly as it is.
//
// Point creation along edges, as in HXT (Marot, Pellerin and Remacle, "One
// machine, one minute, three billion tetrahedra", IJNME 117, 2019, section
// 4): an edge longer than split_length in units of h gets a point one unit
// of h from its end (or its midpoint when it is short), accepted only if no
// vertex is closer than min_spacing * h. The edges are those of each vertex
// in turn, new vertices queued after the old ones, so the volume fills like
// an advancing front from the surface inward (layers about h apart), which
// gives well-spaced points (Frey, Borouchaki and George, "3D Delaunay mesh
// generation coupled with an advancing-front approach", CMAME 157, 1998).
// The front starts from a first layer: the apex of the regular tetrahedron
// over each boundary face (the points a frontal mesher would place first),
// filtered like every candidate; without it the tetrahedra on the boundary
// faces get their apex from whatever edge point lands nearby.
#pragma once

#include <cstdint>
#include <vector>

#include "core/util/progress.h"
#include "core/util/result.h"
#include "core/volume/delaunay3d.h"
#include "core/volume/size_field3d.h"

namespace vm {

struct RefineOptions {
  /// Tag of the region to refine (Delaunay3D::tag).
  int32_t region_tag = 1;
  /// Edges longer than this, in units of h (metric length), get a point.
  double split_length = 1.45;
  /// Candidates closer than this * h to a vertex are rejected.
  double min_spacing = 0.72;
  /// Candidates closer than this * h to a constrained face are rejected
  /// (the boundary is final: no new point hugs it).
  double boundary_spacing = 0.45;
  /// Relative tolerance of the size evaluations (VolumeSizeField::eval): 0
  /// gives exact sizes; t > 0 sizes at most 1 / (1 - t) times too large,
  /// faster inside tubes whose wall sizes vary (the exact minimum visits
  /// the whole wall around the point).
  double size_tolerance = 0;
  /// Seed a first layer: the apex of the regular tetrahedron over each
  /// boundary face (then filtered like every candidate).
  bool first_layer = true;
  /// Upper bound on inserted points (the refinement stops there; reported).
  int64_t max_points = int64_t(1) << 28;
  /// Parallel rounds of the first layer and of the front (phases 2 and
  /// 4): the items (first-layer points, queued vertices) are cut into
  /// `parts` slabs of equal count (along x, y, z in turn), worked at the
  /// same time, each only where it owns the tetrahedra; what a slab cannot
  /// do waits for the next round; after `rounds` rounds, or when fewer than
  /// min_slab_items items per slab are left, one sequential round ends the
  /// phase. A slab may insert 3 vertices per front item in a round; a
  /// round in which one spent that budget with work left (a core much
  /// finer than the wall) adds a round with the budget doubled (at most
  /// budget_rounds such). The mesh depends on these numbers, never on the
  /// thread count. rounds = 0: all sequential. 1 <= parts <= 64. More
  /// slabs than 2 leave most of the work to the sequential round: until
  /// the front reaches it, the lumen's inside is the boundary
  /// triangulation, whose tetrahedra span the vessel and so cross the slab
  /// cuts.
  int parts = 2;
  int rounds = 3;
  int min_slab_items = 4096;
  int budget_rounds = 6;
};

struct RefineStats {
  int64_t vertices_processed = 0;  ///< vertices whose edges were examined
  int64_t candidates = 0;          ///< points proposed (first layer and long edges)
  int64_t size_evaluations = 0;    ///< size field queries
  int64_t inserted = 0;
  int64_t first_layer = 0;          ///< of which first-layer points
  int64_t rejected_spacing = 0;     ///< too close to a vertex
  int64_t rejected_boundary = 0;    ///< too close to a constrained face
  int64_t rejected_outside = 0;     ///< located outside the region
  int64_t rejected_kernel = 0;      ///< the kernel refused (blocked, duplicate, hull)
  int generations = 0;              ///< depth of the front (layers of new vertices)
  int rounds = 0;                   ///< parallel rounds run
  int first_layer_rounds = 0;       ///< of which the first layer's
  int64_t deferred = 0;             ///< items a slab left to a later round
  int64_t sequential_inserted = 0;  ///< of `inserted`, by the sequential rounds
  bool hit_max_points = false;
  double first_layer_seconds = 0;  ///< checks and first layer (part of seconds)
  double seconds = 0;
};

/// Refines the region tagged options.region_tag of `kernel`.
///
/// Preconditions (checked when cheap): the region is closed by constrained
/// faces (every face between a region tetrahedron and another tetrahedron
/// or a ghost is constrained), so insert(p, hint, true) never leaves it;
/// `vertex_h` holds h at every kernel vertex (one double per vertex, > 0,
/// model units; e.g. field(x_i) for the boundary vertices). On return the
/// kernel holds the new vertices (ids from num_vertices() before the call,
/// in insertion order) and vertex_h their h (exact field values).
/// h at a candidate: the field's value (VolumeSizeField::eval, within
/// size_tolerance), searched below the upper bounds that the sizes of the
/// vertices around it give (h is g-Lipschitz).
/// Boundary vertices and constrained faces are never touched: every point
/// is inserted with respect_constraints and at least
/// boundary_spacing * h from constrained faces of the tetrahedra around it.
/// Errors: vertex_h size mismatch or bad options; cancelled by progress.
Status refine_volume(Delaunay3D& kernel, const VolumeSizeField& field,
                     std::vector<double>& vertex_h, const RefineOptions& options,
                     RefineStats* stats, const ProgressFn& progress = {});

}  // namespace vm
