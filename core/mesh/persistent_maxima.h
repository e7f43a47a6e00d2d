// Local maxima of a vertex field with their persistence (the 0-dimensional
// persistent homology of the superlevel sets over the vertex graph, Edelsbrunner,
// Letscher and Zomorodian, "Topological persistence and simplification",
// 2002): lowering a threshold from the top, each maximum starts a region;
// when two regions meet at a vertex, the one with the lower maximum dies
// there, and its persistence is its height above that vertex. Small
// persistence means noise (a bump or a plateau's ripple); a vessel tip's
// persistence, for the geodesic distance from a far point, is about the
// length of its vessel beyond the branching.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/mesh/edge_geodesics.h"

namespace vm {

struct FieldMaximum {
  int32_t vertex = -1;
  double value = 0;
  /// Height above the vertex where its region joins a higher one; infinity
  /// for the highest maximum of each connected part.
  double persistence = 0;
};

/// The local maxima of `field` (one value per graph vertex; vertices with a
/// non-finite value are left out) whose persistence is at least
/// `min_persistence`, by decreasing persistence (ties: decreasing value).
/// Equal values are ordered by vertex index, so a plateau has one maximum.
/// O(n log n).
std::vector<FieldMaximum> persistent_maxima(const VertexGraph& graph, std::span<const double> field,
                                            double min_persistence);

}  // namespace vm
