// Absorbing points the core's boundary recovery added on the viscous
// layer's front (core/volume/boundary_recovery.h) in the layer's top slice
// alone, so that the wall below keeps its triangles (our own method; the
// layer is Marchandise et al.'s, section 2.2, and its prisms are split into
// tetrahedra by Dompierre et al.'s smallest-index rule, core/mesh/
// prism_split.h).
//
// The alternative, refine_layer_columns (refine_layers.h), carries each
// such point down through every layer to the wall and splits the wall's
// triangles there: two triangles of gamma_k 1 split at an edge's midpoint
// have 0.73. Here only the top slice's prisms over the split front
// triangles change: each becomes the tetrahedra of a cone from its
// smallest-id bottom vertex over the faces not containing it (the front's
// pieces, and the side opposite the apex), every side face cut as a fan
// from its smallest-id vertex. That is how split_prism cuts an unsplit prism
// (a cone from its smallest vertex), so the pieces conform with the
// neighbouring split prisms, the slice below and the core's tetrahedra.
#pragma once

#include <cstdint>
#include <vector>

#include "core/layers/layer_mesh.h"
#include "core/util/result.h"

namespace vm {

/// The top slice's tetrahedra over a refined front. Ids: id >= 0 is point
/// id of the layer mesh; id < 0 is new point -1 - id.
struct AbsorbedFront {
  /// The layer's prisms replaced (indices into m.prisms / 6, all in the
  /// top slice), ascending.
  std::vector<int32_t> replaced_prisms;
  /// Their tetrahedra: 4 ids each, tet_volume6 > 0 (checked exactly).
  std::vector<int32_t> tets;
  /// The ring faces at the openings that change: per top-slice rim quad
  /// with new points on its front edge, its 4 ids (layer points: the two
  /// rim columns on layers N - 1 and N) and its opening (index into
  /// m.openings); the triangles replacing its two, 3 ids each, oriented out
  /// of the layer region like ring_triangles, from ring_first[q] to
  /// ring_first[q + 1].
  std::vector<int32_t> ring_quads;
  std::vector<int32_t> ring_opening;
  std::vector<int32_t> ring_first = {0};
  std::vector<int32_t> ring_triangles;
};

/// The tetrahedra replacing the top-slice prisms of inward layer `m` whose
/// front triangles a refinement splits, in the ids above.
/// - triangles: 3 column ids per triangle, oriented like m.front; id <
///   m.wall_vertices is a column (its front point m.layer_vertex(id,
///   m.layers)), id = m.wall_vertices + j new point j. Together they tile
///   the front: each lies in its parent's front triangle, and a new point
///   on an edge of its parent is on that edge (as boundary recovery splits
///   them).
/// - parent: per triangle, the front triangle it lies in.
/// - new_points: 3 doubles per new point.
/// Preconditions: m is inward (m.outward false) with at least one layer.
/// Errors: sizes or ids out of range, a parent whose pieces do not form one
/// disc with its three corners on the boundary, a tetrahedron that is not
/// strictly positive (exact orient3d): the caller then refines the columns
/// instead.
Result<AbsorbedFront> absorb_front_points(const LayerMesh& m, const std::vector<int32_t>& triangles,
                                          const std::vector<int32_t>& parent,
                                          const std::vector<double>& new_points);

}  // namespace vm
