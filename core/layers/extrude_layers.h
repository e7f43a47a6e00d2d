// Boundary-layer extrusion (docs/ARCHITECTURE.md, stage 4): the advancing-layer
// method of Marchandise et al., section 2.2 ("from each surface node a
// direction is picked ... using Gouraud shading ... the nodes are connected
// to form layers of prisms that are subsequently subdivided into
// tetrahedra; care is taken to produce elements of acceptable shape at
// sharp corners and to prevent element overlap in regions of tight
// corners"), after the advancing-layer literature it cites (Kallinderis and
// Ward 1993; Pirzadeh 1996; Garimella and Shephard 2000). Inward it grows
// the viscous layer (seed 4.2: 4 uniform layers of h_BL), outward the
// vessel wall (seed 4.3: 0.1 R in 4 layers).
#pragma once

#include <vector>

#include "core/layers/layer_assembly.h"
#include "core/layers/layer_mesh.h"
#include "core/mesh/surface_mesh.h"
#include "core/util/result.h"

namespace vm {

/// Grows spec.layers layers of prisms from `wall`, inward (into the lumen)
/// or outward (spec.outward), in phases:
///  1. openings: each boundary loop's plane by fit_opening_plane (cap_openings.h)
///     and its rim vertices moved onto it with the same arithmetic as
///     cap_openings, so caps built later on the same wall agree bitwise;
///  2. directions (layer_directions.h): smoothed Gouraud normals, rim
///     directions in their cap plane (into the cap for inward layers, away
///     from it outward), columns near an opening kept from reaching its cap
///     plane, every direction seeing its incident triangles;
///  3. thickness (layer_thickness.h): requested T(v) = F R(v) or the
///     H1 / growth series; each column lengthened (at most 1 / 0.7 times)
///     until its end is T(v) from the triangles of its star, so heights
///     measured from the wall are the requested ones on faceted or creased
///     walls (spec.lean_compensation; without it if no valid layer is
///     found with it); gap limit T <= 2 gap_fraction r(v) cos(d, n) with
///     r the empty-ball radius on the layer side (layer_gap.h);
///  4. local validity (layer_validity.h): per-vertex factors lowered by
///     bisection until every sub-tetrahedron of every prism has the volume
///     margin and every front triangle keeps its shape; the reduction is
///     graded (thickness slope <= spec.gradation next to reduced vertices,
///     layer_thickness.h) after every change;
///  5. verification: exact intersection tests (triangles_intersect,
///     mesh/self_intersection.h) of every pair of the layer's closed
///     boundary that involves a front or ring triangle (wall + front + the
///     rings split as the prisms are; pairs within the wall are the
///     input's); columns of intersecting front or ring triangles are shrunk
///     (x 0.7) and phases 4-5 repeat (at most spec.max_rounds rounds);
///  6. construction of the points, prisms, front and rim columns (rim
///     columns computed in their plane coordinates, so they stay in the
///     plane to rounding), and the statistics.
/// With every sub-tetrahedron positive and the boundary of the layer
/// region (wall, front, rings) free of intersections, the layer region is
/// embedded: no two elements overlap (degree argument: every point inside
/// the boundary is covered exactly once).
///
/// The thickness is reduced (factor < 1) only where phases 3-5 require it;
/// every column keeps all N layers (factor >= 1e-3), scaled uniformly, so the
/// first-layer height shrinks with the total.
///
/// Inputs: `wall` one manifold, consistently outward-oriented surface
/// (open: its boundary loops are the openings, simple loops not sharing
/// vertices; or closed), every vertex used, no degenerate triangle;
/// `radius` the local vessel radius R per wall vertex (model units, e.g.
/// chord_radius(wall), or vessel_radius(wall), or their minimum), may be
/// empty when spec.first_height > 0; `stats` optional.
/// Errors: invalid spec or sizes, a non-manifold, inconsistently oriented or
/// inward-facing wall, isolated vertices, openings sharing a vertex or with
/// fewer than 3 vertices, a degenerate rim, a vertex no direction can
/// extrude from (layer_directions.h), no valid layer within max_rounds.
Result<LayerMesh> extrude_layers(const SurfaceMesh& wall, const std::vector<double>& radius,
                                 const LayerSpec& spec, LayerStats* stats = nullptr);

}  // namespace vm
