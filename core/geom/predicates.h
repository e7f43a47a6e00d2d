// Exact geometric predicates (Shewchuk, "Adaptive precision floating-point
// arithmetic and fast robust geometric predicates", DCG 18, 1997): a
// floating-point evaluation accepted when it exceeds Shewchuk's forward
// error bound, else an exact evaluation in expansion arithmetic. The sign is
// always the sign of the exact determinant for the given doubles. Shared by
// the 2D meshers and the 3D Delaunay stage.
//
// insphere_sos adds symbolic perturbation (Edelsbrunner and Muecke,
// "Simulation of Simplicity", ACM TOG 9, 1990; in the lifted form of
// Devillers and Teillaud, "Perturbations for Delaunay and weighted Delaunay
// 3D triangulations", CGTA 44, 2011): each point's lifted coordinate |p|^2 is
// raised by an infinitesimal whose order is given by its vertex index, so
// that cospherical ties are broken consistently and the 3D Delaunay kernel
// builds one well-defined triangulation of any point set.
#pragma once

#include <cstdint>

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

/// The sign (+1, -1) of insphere(a, b, c, d, e) with the lifted coordinate of
/// each point p raised by eps^(rank of its index), eps -> 0+, where the point
/// with the largest index gets the largest (most significant) raise.
/// Equals the sign of insphere() whenever that is nonzero. On a tie the sign
/// of the first nonzero coefficient is returned; the coefficient of point
/// p's raise is +-orient3d of the other four points, so the result is
/// nonzero whenever the five points are not coplanar (in particular when
/// a, b, c, d span a tetrahedron). Returns 0 only if all five are coplanar.
/// Precondition: the indices are pairwise distinct (they name the points).
/// Geometrically, raising a point's lift pushes it outside: among
/// cospherical points, the one with the largest index is "outside" the
/// sphere of the others.
int insphere_sos(const double* a, const double* b, const double* c, const double* d,
                 const double* e, int64_t ia, int64_t ib, int64_t ic, int64_t id, int64_t ie);

}  // namespace vm
