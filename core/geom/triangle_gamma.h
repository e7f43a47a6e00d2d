// Triangle quality gamma_k of the seed paper (Marchandise et al., section 3):
// gamma = 4 sin a sin b sin c / (sin a + sin b + sin c) = 2 r_in / r_circ,
// 1 for the equilateral triangle, 0 for a degenerate one. The formula alone,
// for the meshers that judge their own triangles (mesh/decimate, mesh2d);
// the measures over a mesh and their summary are quality/triangle_quality.h.
#pragma once

namespace vm {

/// gamma_k of the triangle with corners a, b, c (3 doubles each).
double triangle_gamma(const double* a, const double* b, const double* c);

}  // namespace vm
