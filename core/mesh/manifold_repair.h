// Repair of non-manifold surfaces into manifold sheets, for dirty
// segmentation output: fins hanging on an edge are dropped, the other
// non-manifold edges are split by pairing their triangles in angular order
// around the edge (the usual "cutting" step of Gueziec, Taubin, Lazarus and
// Horn, "Cutting and stitching: converting sets of polygons to manifold
// surfaces", IEEE TVCG 2001), every vertex where several triangle fans
// meet is duplicated once per fan, and a local twist (a crosscap of a few
// triangles, found as a short orientation-reversing cycle) is cut out.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/geom/vec3.h"
#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

struct ManifoldRepairStats {
  /// Triangles removed because they hung on a non-manifold edge with both
  /// of their other edges free (fins, e.g. a stray triangle of a mask).
  size_t fins_removed = 0;
  Vec3 fin_example{};  ///< the centroid of one removed fin
  /// Non-manifold edges (3 or more triangles) split into manifold sheets.
  size_t edges_split = 0;
  Vec3 edge_example{};  ///< the midpoint of one split edge
  /// Vertices where several fans met, and the copies added for them.
  size_t vertices_split = 0;
  size_t vertex_copies = 0;
  Vec3 vertex_example{};
  /// Triangles removed because orienting them was contradictory (a local
  /// twist: they leave holes behind, for the hole filling to close).
  size_t twisted_removed = 0;
  Vec3 twisted_example{};
};

/// Drops fins (a triangle on a non-manifold edge whose two other edges are
/// free; repeated while some are left), then splits each remaining edge of 3
/// or more triangles: the triangles are sorted by the angle of their third
/// corner around the edge and paired with a neighbor in that order, choosing
/// the pairing whose pairs traverse the edge in opposite directions (a
/// consistent sheet) where the orientation tells; with an odd count one
/// triangle is left with a free edge there. The edge's end vertices are
/// then duplicated per fan (split_fans), so each pair becomes its own edge.
/// `labels` (one per triangle, or null) follow the removals. Vertices and
/// triangles keep their order; copies are appended. Precondition: no
/// triangle with a repeated vertex, no duplicate triangles. `adj`, when
/// given, is build_adjacency(mesh) (saves building it again); on return it
/// is the adjacency of the repaired mesh either way when given.
void split_nonmanifold_edges(SurfaceMesh& mesh, std::vector<int32_t>* labels,
                             ManifoldRepairStats& stats, TriangleAdjacency* adj = nullptr);

/// Duplicates every vertex whose triangles form several fans (sets of
/// triangles connected across edges at the vertex that have exactly two
/// triangles): the fan with the vertex's lowest triangle keeps it, each
/// other fan gets a copy at the same place, appended to the points.
/// Triangles keep their order and orientation. Precondition: no edge with
/// 3 or more triangles (run split_nonmanifold_edges first), else such
/// edges are left as they are. `adj`, when given, is build_adjacency(mesh).
void split_nonmanifold_vertices(SurfaceMesh& mesh, ManifoldRepairStats& stats,
                                const TriangleAdjacency* adj = nullptr);

/// Makes a surface orientable that is not only because of a local twist
/// (a crosscap of a few triangles): while orienting across the edges of
/// exactly two triangles is contradictory, the triangles on an
/// orientation-reversing cycle of at most 6 triangles are removed (with
/// their labels), up to 3 rounds, while at most
/// `budget` triangles go, none of them touching a free edge of the input
/// (so a band is never cut across). When no short cycle is found (a
/// Moebius band: its shortest one runs its whole length) or the twist
/// needs more, the mesh is put back as it was. Returns the triangles
/// removed. Cost: O(triangles * 2^6) when the surface is non-orientable.
/// `adj`, when given, is build_adjacency(mesh); it is rebuilt for the
/// returned mesh when triangles were removed.
size_t remove_orientation_twists(SurfaceMesh& mesh, std::vector<int32_t>* labels,
                                 ManifoldRepairStats& stats, size_t budget,
                                 TriangleAdjacency* adj = nullptr);

}  // namespace vm
