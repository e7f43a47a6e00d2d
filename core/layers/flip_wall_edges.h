// Wall edges flipped instead of split (our own method, on Marchandise et
// al.'s layers, section 2.2): where boundary recovery (core/volume/
// boundary_recovery.h) cannot recover a wall edge by flips in the volume, a
// Steiner point would split the two wall triangles there (gamma_k 1 becomes
// 0.73 at best, far less on stretched triangles). Flipping the edge on the
// wall itself, as the remesher's swaps do on the input surface, keeps the
// wall's triangles whole when the two triangles are nearly coplanar; the
// layers' columns over them are flipped with it (every slice's prisms over
// the new pair), when all their tetrahedra stay positive.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/layers/layer_mesh.h"

namespace vm {

/// Whether the surface through a, b, c, d (3 doubles each) may trade
/// triangles (a, b, c), (b, a, d) for (c, a, d), (d, b, c): the new pair
/// folds nowhere (each new normal within 90 degrees of each old one), the
/// two diagonals are within kWallFlipGap of the shorter's length of each
/// other (the surface moves by at most that), and the pair's smaller
/// gamma_k falls by at most kWallFlipQualityLoss.
inline constexpr double kWallFlipGap = 0.1;
inline constexpr double kWallFlipQualityLoss = 0.05;
bool wall_flip_ok(const double* a, const double* b, const double* c, const double* d);

/// Whether layer m's columns over the flipped pair make valid prisms on
/// every slice: each prism's three smallest-index tetrahedra (prism_split.h)
/// strictly positive (exact). a, b, c, d are column ids (< m.wall_vertices),
/// named as in wall_flip_ok.
bool layer_flip_ok(const LayerMesh& m, int32_t a, int32_t b, int32_t c, int32_t d);

/// m over another triangulation of the same wall vertices (3 column ids a
/// triangle, oriented like the wall; e.g. m's with edges flipped): prisms
/// and front rebuilt, columns and openings kept.
LayerMesh retriangulate_layer(const LayerMesh& m, const std::vector<int32_t>& triangles);

/// The rule recover_boundary's may_flip_surface follows for a core whose
/// boundary is the wall (no viscous layer: `inner` null; `points` the
/// core boundary's, its first `wall_vertices` the wall's) or the viscous layer's front with its
/// prisms kept (keep_prisms; the wall is then inner's layer 0): tag 0 (the wall or front), ids of
/// wall vertices (< the wall's vertex count), wall_flip_ok on the wall (and on the front),
/// layer_flip_ok for each layer. Empty (no surface flips) when the viscous layer's prisms are
/// split: its top slice takes the Steiner points and the wall keeps its triangles
/// (absorb_front_points.h).
std::function<bool(int32_t, int32_t, int32_t, int32_t, int32_t)> wall_flip_rule(
    const LayerMesh* inner, const LayerMesh* outer, const std::vector<double>& points,
    size_t wall_vertices, bool keep_prisms);

}  // namespace vm
