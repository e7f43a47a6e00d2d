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

#include <algorithm>
#include <cmath>
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

// ---- Semi-static filters for hot paths (the 3D Delaunay kernel): the
// fast-stage determinants of predicates.cpp, accepted against a bound on
// Shewchuk's permanent from the largest coordinate difference m (permanent
// <= 6 m^3 for orient3d, 72 m^5 for insphere), which costs a few max()
// instead of the permanent. When the bound does not decide (or m is so
// small or large that the bound could under- or overflow), the dynamically
// filtered exact predicate decides. The sign is always exact; the
// magnitude is that of whichever stage decided.
namespace predicates_detail {
constexpr double kEps = 0x1p-53;
constexpr double kO3Static = (7.0 + 56.0 * kEps) * kEps * 6 * (1 + 1e-12);
constexpr double kIsStatic = (16.0 + 224.0 * kEps) * kEps * 72 * (1 + 1e-12);

// The largest |x| (a max tree, no temporary array).
inline double max_abs(double a, double b, double c) {
  return std::max(std::max(std::fabs(a), std::fabs(b)), std::fabs(c));
}
inline double max_abs(double a, double b, double c, double d, double e, double f) {
  return std::max(max_abs(a, b, c), max_abs(d, e, f));
}
inline double max_abs(double a, double b, double c, double d, double e, double f, double g,
                      double h, double i) {
  return std::max(max_abs(a, b, c, d, e, f), max_abs(g, h, i));
}

// Two doubles in one vector (GCC/Clang vector extension).
typedef double V2 __attribute__((vector_size(16)));
inline V2 load2(const double* p) {
  V2 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}

/// insphere_fast() after its static stage: the semi-static bound on the
/// fast-stage determinant det, else the exact predicate.
inline double insphere_semi_static(const double* a, const double* b, const double* c,
                                   const double* d, const double* e, double det) {
  const double m = std::max(
      max_abs(a[0] - e[0], a[1] - e[1], a[2] - e[2], b[0] - e[0], b[1] - e[1], b[2] - e[2]),
      max_abs(c[0] - e[0], c[1] - e[1], c[2] - e[2], d[0] - e[0], d[1] - e[1], d[2] - e[2]));
  if (m > 1e-55 && m < 1e55) {
    const double m2 = m * m;
    const double bound = kIsStatic * m2 * m2 * m;
    if (det > bound || -det > bound) return det;
  }
  return insphere(a, b, c, d, e);
}

}  // namespace predicates_detail

/// Static filter bounds for the *_fast predicates below, from an upper
/// bound `extent` on every coordinate difference of the points (the largest
/// side of their bounding box): the fast-stage determinant of points in
/// that box is certain when its magnitude exceeds the bound, which costs
/// one comparison. Infinity (never decides) when the extent is not in the
/// range where the bound is safe from under- and overflow.
inline double orient3d_static_bound(double extent) {
  if (!(extent > 1e-55 && extent < 1e55)) return HUGE_VAL;
  return predicates_detail::kO3Static * extent * extent * extent;
}
inline double insphere_static_bound(double extent) {
  if (!(extent > 1e-55 && extent < 1e55)) return HUGE_VAL;
  const double e2 = extent * extent;
  return predicates_detail::kIsStatic * e2 * e2 * extent;
}

/// orient3d() with a static filter (static_bound from
/// orient3d_static_bound(), if the caller knows a box of the points), then
/// a semi-static one, first (same sign).
[[gnu::always_inline]] inline double orient3d_fast(const double* a, const double* b,
                                                   const double* c, const double* d,
                                                   double static_bound = HUGE_VAL) {
  const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  const double det =
      adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) + cdz * (adx * bdy - bdx * ady);
  if (det > static_bound || -det > static_bound) return det;
  const double m = predicates_detail::max_abs(adx, ady, adz, bdx, bdy, bdz, cdx, cdy, cdz);
  if (m > 1e-55 && m < 1e55) {
    const double bound = predicates_detail::kO3Static * m * m * m;
    if (det > bound || -det > bound) return det;
  }
  return orient3d(a, b, c, d);
}

/// insphere() with a static filter (static_bound from
/// insphere_static_bound()), then a semi-static one, first (same sign).
/// The static stage computes the fast-stage determinant two lanes at a
/// time (points a, c and b, d side by side, GCC/Clang vector extensions,
/// SSE2 or wasm SIMD, else scalar code): every lane performs the scalar
/// formula's operations in its order, so the value, hence the sign and the
/// filter's decision, is the scalar one to the bit on every target.
[[gnu::always_inline]] inline double insphere_fast(const double* a, const double* b,
                                                   const double* c, const double* d,
                                                   const double* e,
                                                   double static_bound = HUGE_VAL) {
  using V = predicates_detail::V2;
  using predicates_detail::load2;
  const V e01 = load2(e), e2 = {e[2], e[2]}, flip = {1.0, -1.0};
  const V ea = load2(a) - e01, eb = load2(b) - e01, ec = load2(c) - e01, ed = load2(d) - e01;
  // x, y and z of (a, c) and of (b, d), minus e.
  const V x_ac = __builtin_shufflevector(ea, ec, 0, 2),
          y_ac = __builtin_shufflevector(ea, ec, 1, 3);
  const V x_bd = __builtin_shufflevector(eb, ed, 0, 2),
          y_bd = __builtin_shufflevector(eb, ed, 1, 3);
  const V z_ac = V{a[2], c[2]} - e2, z_bd = V{b[2], d[2]} - e2;
  const V y_ca = __builtin_shufflevector(y_ac, y_ac, 1, 0);
  const V y_db = __builtin_shufflevector(y_bd, y_bd, 1, 0);
  const V x_ca = __builtin_shufflevector(x_ac, x_ac, 1, 0);
  // 2x2 minors: (ab, cd), (bc, da), (ac, bd).
  const V ab_cd = x_ac * y_bd - x_bd * y_ac;
  const V bc_da = x_bd * y_ca - x_ca * y_bd;
  const V p = x_ac * y_ca, q = x_bd * y_db;
  const V ac_bd = __builtin_shufflevector(p, q, 0, 2) - __builtin_shufflevector(p, q, 1, 3);
  const V ac_ac = __builtin_shufflevector(ac_bd, ac_bd, 0, 0);
  const V bd_bd = __builtin_shufflevector(ac_bd, ac_bd, 1, 1);
  // 3x3 minors (abc, cda) and (bcd, dab); x + y as x - (-y), which is exact.
  const V abc_cda =
      z_ac * bc_da - z_bd * flip * ac_ac + __builtin_shufflevector(z_ac, z_ac, 1, 0) * ab_cd;
  const V bcd_dab = z_bd * __builtin_shufflevector(ab_cd, ab_cd, 1, 0) -
                    __builtin_shufflevector(z_ac, z_ac, 1, 0) * flip * bd_bd +
                    __builtin_shufflevector(z_bd, z_bd, 1, 0) * bc_da;
  const V lift_ac = x_ac * x_ac + y_ac * y_ac + z_ac * z_ac;
  const V lift_bd = x_bd * x_bd + y_bd * y_bd + z_bd * z_bd;
  // (dlift abc - clift dab, blift cda - alift bcd).
  const V u = __builtin_shufflevector(lift_bd, lift_bd, 1, 0) * abc_cda -
              __builtin_shufflevector(lift_ac, lift_ac, 1, 0) *
                  __builtin_shufflevector(bcd_dab, bcd_dab, 1, 0);
  const double det = u[0] + u[1];
  if (det > static_bound || -det > static_bound) return det;
  return predicates_detail::insphere_semi_static(a, b, c, d, e, det);
}

}  // namespace vm
