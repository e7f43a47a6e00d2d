// Exact geometric predicates (Shewchuk, "Adaptive precision floating-point
// arithmetic and fast robust geometric predicates", DCG 18, 1997): a
// floating-point evaluation accepted when it exceeds Shewchuk's forward
// error bound, else an exact evaluation in expansion arithmetic. The sign is
// always the sign of the exact determinant for the given doubles. Shared by
// the 2D meshers (issue 3) and the 3D Delaunay stage (issue 4).
#pragma once

namespace vm {

/// > 0 if a, b, c (2 doubles each) turn counterclockwise, < 0 clockwise,
/// 0 if collinear. The magnitude is only meaningful on the fast path.
double orient2d(const double* a, const double* b, const double* c);

/// > 0 if d lies inside the circle through a, b, c (counterclockwise), < 0
/// outside, 0 on it. Precondition for the meaning of the sign: a, b, c ccw.
double incircle(const double* a, const double* b, const double* c, const double* d);

/// > 0 if d lies below the plane of a, b, c (a, b, c counterclockwise seen
/// from above), i.e. the sign of det[a-d, b-d, c-d]; 0 if coplanar.
double orient3d(const double* a, const double* b, const double* c, const double* d);

/// > 0 if e lies inside the sphere through a, b, c, d when orient3d(a, b, c,
/// d) > 0; 0 if cospherical.
double insphere(const double* a, const double* b, const double* c, const double* d,
                const double* e);

}  // namespace vm
