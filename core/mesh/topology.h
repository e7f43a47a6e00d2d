// Topological and geometric analysis of an indexed triangle surface:
// components, boundary loops (openings), non-manifold edges, Euler
// characteristic and genus.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh/adjacency.h"
#include "core/mesh/surface_mesh.h"

namespace vm {

/// One boundary loop of the surface, i.e. an opening of the vessel.
struct Opening {
  std::vector<int32_t> loop;  ///< vertex indices in order, not repeated
  double perimeter = 0;
  /// sqrt(|vector area| / pi) of the loop closed by a fan from its centroid:
  /// the radius of the disk of the same area.
  double radius = 0;
  std::array<double, 3> centroid{};  ///< mean of the loop's edge midpoints
                                     ///< weighted by edge length
  std::array<double, 3> normal{};    ///< unit vector area of the loop
};

struct TopologyReport {
  size_t vertices = 0;
  size_t triangles = 0;
  size_t edges = 0;
  int components = 0;
  /// Openings sorted by decreasing radius.
  std::vector<Opening> openings;
  /// Boundary loops of fewer than three vertices (the free edges of a fin
  /// on a non-manifold edge, a cut of no width): no area, never an opening;
  /// counted as boundaries in the genus.
  std::vector<Opening> slits;
  size_t boundary_edges = 0;
  size_t nonmanifold_edges = 0;  ///< edges with more than two triangles
  /// Vertices whose incident triangles form more than one fan (bow-ties).
  size_t nonmanifold_vertices = 0;
  long euler_characteristic = 0;  ///< V - E + F
  /// Total genus sum over components of (2 - chi_i - b_i) / 2; -1 when not
  /// defined (non-manifold edges or vertices).
  int genus = -1;
  bool closed = false;  ///< no boundary edges
  /// One example location per problem kind, for error messages (x y z).
  std::array<double, 3> nonmanifold_edge_example{};
  /// component id per triangle (0..components-1), largest component is 0.
  std::vector<int32_t> triangle_component;
  std::vector<size_t> component_triangles;  ///< triangle count per component
};

/// The perimeter, radius, centroid and normal of a loop of `mesh`'s
/// vertices (in order, not repeated).
Opening describe_loop(const SurfaceMesh& mesh, std::vector<int32_t> loop);

/// Analyzes `mesh`. Precondition: no triangle with a repeated vertex.
/// Boundary loops through a bow-tie vertex are split at that vertex by
/// following the triangle fans, so each loop is a simple cycle.
TopologyReport analyze_topology(const SurfaceMesh& mesh);

/// Same, reusing an adjacency already built for `mesh`.
TopologyReport analyze_topology(const SurfaceMesh& mesh, const TriangleAdjacency& adj);

/// Keeps only the triangles of component `component` (as numbered by
/// `report.triangle_component`) and drops unused vertices.
SurfaceMesh extract_component(const SurfaceMesh& mesh, const TopologyReport& report, int component);

}  // namespace vm
