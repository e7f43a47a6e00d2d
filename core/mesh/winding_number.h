// The generalized winding number of a triangle surface at a point: the
// signed solid angle the surface subtends there, over 4 pi (Jacobson, Kavan
// and Sorkine-Hornung, "Robust inside-outside segmentation using generalized
// winding numbers", SIGGRAPH 2013). It is 1 inside and 0 outside a closed,
// outward-oriented surface, k inside k overlapping shells, and degrades
// gracefully where the surface has holes, duplicates, crossings or open
// sheets: {w >= 1/2} is then the union of what the pieces enclose. Evaluated
// fast with a box hierarchy whose far nodes count as dipoles (Barill,
// Dickson, Schmidt, Levin and Jacobson, "Fast winding numbers for soups and
// clouds", SIGGRAPH 2018: the first-order expansion).
#pragma once

#include <vector>

#include "core/mesh/surface_mesh.h"
#include "core/mesh/triangle_bvh.h"

namespace vm {

/// The hierarchy and, per node, its dipole: the sum of its triangles' area
/// vectors (half the cross products: 3 doubles), their area-weighted
/// centroid (3 doubles), and the distance from that centroid to the node's
/// farthest box corner (1 double).
struct WindingNumberTree {
  TriangleBvh bvh;
  std::vector<double> area_vector;  ///< 3 per node
  std::vector<double> center;       ///< 3 per node
  std::vector<double> reach;        ///< 1 per node
};

/// Builds the tree over all triangles of `mesh` (any soup: degenerate,
/// duplicate and crossing triangles are fine). O(n log n). The mesh must
/// outlive the queries.
WindingNumberTree build_winding_number_tree(const SurfaceMesh& mesh);

/// The winding number of `mesh` at q (3 doubles): exact solid angles (van
/// Oosterom and Strackee's formula) for the triangles of nodes nearer than
/// `beta` times their reach, the node's dipole for the others (relative
/// error about (1 / beta)^2 of a node's share). A point on a triangle gets
/// that triangle's contribution as 0.
double winding_number(const SurfaceMesh& mesh, const WindingNumberTree& tree, const double* q,
                      double beta = 2.5);

/// The exact winding number (all triangles, no approximation): O(n), for
/// tests and small surfaces.
double winding_number_exact(const SurfaceMesh& mesh, const double* q);

}  // namespace vm
