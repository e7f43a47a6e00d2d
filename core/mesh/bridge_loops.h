// A strip of triangles joining two closed loops of vertices: the classical
// optimal tiling between two contours (Fuchs, Kedem and Uselton, "Optimal
// surface reconstruction from planar contours", CACM 1977) by dynamic
// programming over the toroidal grid of rungs, with the cost the total
// length of the rungs (the edges between the loops) and the alignment the
// best of a few starting rungs. Used to sew a re-surfaced region to the
// surface around it (core/prepare/resurface_crossings.h).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace vm {

/// Triangles (3 vertex ids each) of an annulus between loop `a` and loop
/// `b` (vertex ids into `points`, 3 doubles per vertex; each loop 3 or more
/// vertices, in order, first not repeated), both traversed the same way
/// around the strip. Every edge of `a` and of `b` (between consecutive
/// vertices, with wrap-around) is used by exactly one triangle; the
/// triangles are (a_i, a_i+1, b_j) and (a_i, b_j+1, b_j), so they are
/// consistently oriented among themselves. Starts are tried from the
/// `starts` vertices of `b` nearest a's first vertex; O(starts |a| |b|).
std::vector<int32_t> bridge_loops(const std::vector<double>& points, std::span<const int32_t> a,
                                  std::span<const int32_t> b, int starts = 8);

/// How the loops run relative to each other: the sum, over the vertices of
/// `a`, of the dot product of a's direction there with b's direction at the
/// nearest vertex of b. Positive: the same way around; negative: opposite.
double loops_agreement(const std::vector<double>& points, std::span<const int32_t> a,
                       std::span<const int32_t> b);

}  // namespace vm
