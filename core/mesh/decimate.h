// Decimation of an oversampled surface by half-edge collapses ordered by
// quadric error (Garland and Heckbert, "Surface simplification using quadric
// error metrics", SIGGRAPH 1997), within a distance and an edge length per
// vertex, without changing the topology (the link condition of Dey et al.,
// "Topology preserving edge contraction", 1999) or folding a triangle.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/mesh/surface_mesh.h"

namespace vm {

/// The limits of decimate_surface, per input vertex (num_vertices values
/// each, model units, > 0).
struct DecimateLimits {
  /// A collapse onto or from vertex v keeps the area-weighted mean squared
  /// distance of the merged vertex to the input's planes below max_error[v]^2.
  std::span<const double> max_error;
  /// No collapse makes an edge at v longer than max_edge[v].
  std::span<const double> max_edge;
  /// A collapse keeps every changed triangle's gamma_k at least this (or
  /// at least its gamma_k before, when that was lower).
  double min_quality = 0.25;
  /// ... and its normal within this angle (degrees) of the normal before.
  double max_normal_turn_degrees = 45;
  /// ... and no vertex with more neighbours than this (or than it had).
  int max_valence = 10;
};

/// The decimated surface and where its vertices come from.
struct DecimatedSurface {
  /// A subset of the input's vertices (in input order) and the triangles
  /// left, oriented like the input's.
  SurfaceMesh mesh;
  /// Per output vertex: its index in the input (increasing).
  std::vector<int32_t> input_vertex;
};

/// Collapses edges of `input` (manifold, consistently oriented, no triangle
/// with a repeated vertex) cheapest first while the limits allow.
/// Boundary (opening) vertices are kept, so every opening keeps its loop;
/// genus and components are unchanged. Deterministic (ties by index).
DecimatedSurface decimate_surface(const SurfaceMesh& input, const DecimateLimits& limits);

}  // namespace vm
