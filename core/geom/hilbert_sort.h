// Points ordered along a 3D Hilbert curve, so that points near in the order
// are near in space: one sort of a set (hilbert_sort: for locality, e.g. the
// wall's vertex numbering, the decimation's, the refinement's queues), or,
// for incremental Delaunay insertion (the volume kernel), Biased Randomized
// Insertion Order (Amenta, Choi and Rote, "Incremental constructions con
// BRIO", SoCG 2003) with each round ordered along the curve (Hilbert index
// by Skilling, "Programming the Hilbert curve", AIP Conf. Proc. 707, 2004).
// Rounds keep the expected-case guarantees of a random order; the curve
// order inside a round makes consecutive points close, so the
// point-location walk from the previous insertion is short.
#pragma once

#include <cstdint>
#include <vector>

namespace vm {

/// Hilbert index of the grid cell (x, y, z), each coordinate < 2^bits,
/// 1 <= bits <= 21. Consecutive indices are face-adjacent cells; the map is
/// a bijection of [0, 2^bits)^3 onto [0, 2^(3 bits)).
uint64_t hilbert_index_3d(uint32_t x, uint32_t y, uint32_t z, int bits);

struct SpatialSortOptions {
  /// Each round holds this fraction of the points of the rounds after it
  /// (first round smallest). 0.125 gives few, large rounds (as CGAL's
  /// multiscale sort does); Amenta-Choi-Rote's rounds use 0.5.
  double round_ratio = 0.125;
  /// Rounds smaller than this are merged into the first one.
  int64_t min_round = 64;
  /// Seed of the random assignment to rounds (deterministic output).
  uint64_t seed = 0x9e3779b97f4a7c15ull;
};

/// A permutation of [0, n) (n = points.size() / 3) in BRIO order: rounds of
/// increasing size, each sorted along a Hilbert curve over the bounding box
/// of the whole set (10 bits per axis). points: 3 doubles per point, finite.
std::vector<int32_t> brio_hilbert_order(const std::vector<double>& points,
                                        const SpatialSortOptions& options = {});

/// A permutation of `ids` (indices into points) sorted along the Hilbert
/// curve of the bounding box of those points (10 bits per axis); ties keep
/// their input order (stable).
void hilbert_sort(const std::vector<double>& points, int32_t* ids, int64_t count);

}  // namespace vm
