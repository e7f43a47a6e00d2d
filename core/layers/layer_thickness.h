// Thickness of the boundary layer per wall vertex (Marchandise et al.,
// section 2.2 and 4.2-4.3: a viscous layer of N layers of given first height
// and growth, or a thickness proportional to the local radius, e.g. the
// vessel wall of 0.1 R in 4 layers) and the smooth reduction of it where the
// layer has no room.
#pragma once

#include <vector>

#include "core/layers/layer_geometry.h"
#include "core/layers/layer_mesh.h"
#include "core/mesh/surface_mesh.h"
#include "core/util/result.h"

namespace vm {

/// The requested total thickness per wall vertex: spec.thickness_fraction *
/// radius[v], or, when spec.first_height > 0, the sum of the N heights
/// first_height * growth^k (radius then unused and may be empty).
/// Errors: invalid spec values, a radius vector of the wrong length, a
/// non-finite or non-positive radius.
Result<std::vector<double>> requested_thickness(const LayerSpec& spec,
                                                const std::vector<double>& radius, size_t nv);

/// Cumulative height fractions of the layers (N + 1 values from 0 to 1):
/// fraction[k] = (growth^k - 1) / (growth^N - 1), k / N for growth 1.
std::vector<double> layer_fractions(const LayerSpec& spec);

/// Makes the reduction gradual: the achieved thickness a(v) = factor[v] *
/// requested[v] of a vertex next to a reduced vertex u is lowered to at most
/// a(u) + gradation |uv|, and so on outward from every reduced vertex (a
/// Dijkstra sweep by increasing thickness), so a reduction ramps in with
/// slope <= gradation while vertices far from any reduction keep their
/// requested thickness whatever their neighbors request. Factors only
/// decrease (and are at least min_factor).
void grade_reduction(const SurfaceMesh& wall, const layers::VertexRings& rings,
                     const std::vector<double>& requested, double gradation, double min_factor,
                     std::vector<double>& factor);

}  // namespace vm
