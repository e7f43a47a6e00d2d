// Filtered exact predicates (Shewchuk 1997). Fast path: the determinant in
// doubles, accepted when its magnitude exceeds the published forward error
// bound (ccwerrboundA, iccerrboundA, o3derrboundA, isperrboundA) times the
// permanent. Otherwise the same determinant (expanded about the last point)
// is evaluated exactly in expansion arithmetic; its estimate has the exact
// sign.
#include "core/geom/predicates.h"

#include <algorithm>
#include <cmath>

#include "core/geom/error_free.h"
#include "core/geom/expansion.h"

namespace vm {
namespace {

using exact::Expansion;

constexpr double kEps = 0x1p-53;  // half an ulp of 1
constexpr double kOrient2dBound = (3.0 + 16.0 * kEps) * kEps;
constexpr double kIncircleBound = (10.0 + 96.0 * kEps) * kEps;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEps) * kEps;
constexpr double kInsphereBound = (16.0 + 224.0 * kEps) * kEps;

Expansion diff(double a, double b) { return Expansion::difference(a, b); }

// 2x2 determinant |a b; c d| of expansions.
Expansion det2(const Expansion& a, const Expansion& b, const Expansion& c, const Expansion& d) {
  return a * d - b * c;
}

double orient2d_exact(const double* a, const double* b, const double* c) {
  Expansion acx = diff(a[0], c[0]), acy = diff(a[1], c[1]);
  Expansion bcx = diff(b[0], c[0]), bcy = diff(b[1], c[1]);
  return det2(acx, acy, bcx, bcy).estimate();
}

double incircle_exact(const double* a, const double* b, const double* c, const double* d) {
  Expansion adx = diff(a[0], d[0]), ady = diff(a[1], d[1]);
  Expansion bdx = diff(b[0], d[0]), bdy = diff(b[1], d[1]);
  Expansion cdx = diff(c[0], d[0]), cdy = diff(c[1], d[1]);
  Expansion alift = adx * adx + ady * ady;
  Expansion blift = bdx * bdx + bdy * bdy;
  Expansion clift = cdx * cdx + cdy * cdy;
  Expansion det = alift * det2(bdx, bdy, cdx, cdy) + blift * det2(cdx, cdy, adx, ady) +
                  clift * det2(adx, ady, bdx, bdy);
  return det.estimate();
}

// det[a-d; b-d; c-d] with the differences given as expansions.
Expansion det3(const Expansion* a, const Expansion* b, const Expansion* c) {
  return a[2] * det2(b[0], b[1], c[0], c[1]) + b[2] * det2(c[0], c[1], a[0], a[1]) +
         c[2] * det2(a[0], a[1], b[0], b[1]);
}

double orient3d_exact(const double* a, const double* b, const double* c, const double* d) {
  Expansion ad[3], bd[3], cd[3];
  for (int k = 0; k < 3; ++k) {
    ad[k] = diff(a[k], d[k]);
    bd[k] = diff(b[k], d[k]);
    cd[k] = diff(c[k], d[k]);
  }
  return det3(ad, bd, cd).estimate();
}

double insphere_exact(const double* a, const double* b, const double* c, const double* d,
                      const double* e) {
  Expansion ae[3], be[3], ce[3], de[3];
  for (int k = 0; k < 3; ++k) {
    ae[k] = diff(a[k], e[k]);
    be[k] = diff(b[k], e[k]);
    ce[k] = diff(c[k], e[k]);
    de[k] = diff(d[k], e[k]);
  }
  auto lift = [](const Expansion* p) { return p[0] * p[0] + p[1] * p[1] + p[2] * p[2]; };
  // Cofactor expansion along the lift column of the 4x4 determinant
  // [p - e, |p - e|^2] for p = a, b, c, d.
  Expansion det = lift(de) * det3(ae, be, ce) - lift(ce) * det3(de, ae, be) +
                  lift(be) * det3(ce, de, ae) - lift(ae) * det3(be, ce, de);
  return det.estimate();
}

// Shewchuk's adaptive stage B on fixed-size arrays (no allocation): the
// determinant of the rounded coordinate differences, evaluated exactly in
// expansion arithmetic of bounded length. When every difference is exact
// (common for nearby points: Sterbenz's lemma) it is the exact determinant;
// otherwise it differs from it by at most errboundB * permanent (Shewchuk
// 1997, o3derrboundB, isperrboundB), which decides most of the remaining
// cases. What stage B cannot decide goes to the general exact path above.
namespace fixed {

using exact::two_product;
using exact::two_sum;

inline bool exact_diff(double a, double b, double& d) {
  double y;
  two_sum(a, -b, d, y);
  return y == 0;
}

// h = e + f (Shewchuk's Theorem 13 with Two-Sum throughout, zero
// elimination). e, f increasing magnitude, nonoverlapping; h may not alias.
int sum(int elen, const double* e, int flen, const double* f, double* h) {
  constexpr int kMax = 1200;
  double g[kMax];
  int i = 0, j = 0, n = 0;
  while (i < elen && j < flen) g[n++] = std::fabs(e[i]) <= std::fabs(f[j]) ? e[i++] : f[j++];
  while (i < elen) g[n++] = e[i++];
  while (j < flen) g[n++] = f[j++];
  if (n == 0) return 0;
  int m = 0;
  double q = g[0];
  for (int k = 1; k < n; ++k) {
    double qn, hh;
    two_sum(q, g[k], qn, hh);
    if (hh != 0) h[m++] = hh;
    q = qn;
  }
  if (q != 0 || m == 0) h[m++] = q;
  return m;
}

// h = b * e (scale-expansion with zero elimination).
int scale(int elen, const double* e, double b, double* h) {
  if (elen == 0 || b == 0) return 0;
  int m = 0;
  double q, hh;
  two_product(e[0], b, q, hh);
  if (hh != 0) h[m++] = hh;
  for (int i = 1; i < elen; ++i) {
    double p1, p0, s;
    two_product(e[i], b, p1, p0);
    two_sum(q, p0, s, hh);
    if (hh != 0) h[m++] = hh;
    two_sum(p1, s, q, hh);
    if (hh != 0) h[m++] = hh;
  }
  if (q != 0 || m == 0) h[m++] = q;
  return m;
}

// h = e * f.
int product(int elen, const double* e, int flen, const double* f, double* h) {
  double part[64], acc[1200], tmp[1200];
  int alen = 0;
  for (int i = 0; i < flen; ++i) {
    int plen = scale(elen, e, f[i], part);
    int n = sum(alen, acc, plen, part, tmp);
    std::copy(tmp, tmp + n, acc);
    alen = n;
  }
  std::copy(acc, acc + alen, h);
  return alen;
}

// h = a * b - c * d for doubles.
int det2(double a, double b, double c, double d, double* h) {
  double x[2], y[2];
  two_product(a, b, x[1], x[0]);
  two_product(-c, d, y[1], y[0]);
  double xs[2], ys[2];
  int xl = 0, yl = 0;
  for (double t : {x[0], x[1]})
    if (t != 0) xs[xl++] = t;
  for (double t : {y[0], y[1]})
    if (t != 0) ys[yl++] = t;
  return sum(xl, xs, yl, ys, h);
}

double estimate(int n, const double* e) {
  double s = 0;
  for (int i = 0; i < n; ++i) s += e[i];
  return s;
}

// s1 * m1 + s2 * m2 + s3 * m3 for doubles s and 4-term expansions m.
int combo3(double s1, int l1, const double* m1, double s2, int l2, const double* m2, double s3,
           int l3, const double* m3, double* h) {
  double p1[8], p2[8], p3[8], t[16];
  int n1 = scale(l1, m1, s1, p1), n2 = scale(l2, m2, s2, p2), n3 = scale(l3, m3, s3, p3);
  int nt = sum(n1, p1, n2, p2, t);
  return sum(nt, t, n3, p3, h);
}

constexpr double kEpsB = 0x1p-53;
constexpr double kOrient3dBoundB = (3.0 + 28.0 * kEpsB) * kEpsB;
constexpr double kInsphereBoundB = (5.0 + 72.0 * kEpsB) * kEpsB;

// orient3d by stage B; false if undecided.
bool orient3d(const double* a, const double* b, const double* c, const double* d, double permanent,
              double& out) {
  double ad[3], bd[3], cd[3];
  bool exact = true;
  for (int k = 0; k < 3; ++k) {
    exact = exact_diff(a[k], d[k], ad[k]) && exact;
    exact = exact_diff(b[k], d[k], bd[k]) && exact;
    exact = exact_diff(c[k], d[k], cd[k]) && exact;
  }
  double bc[4], ca[4], ab[4], det[24];
  int nbc = det2(bd[0], cd[1], cd[0], bd[1], bc);
  int nca = det2(cd[0], ad[1], ad[0], cd[1], ca);
  int nab = det2(ad[0], bd[1], bd[0], ad[1], ab);
  int n = combo3(ad[2], nbc, bc, bd[2], nca, ca, cd[2], nab, ab, det);
  out = estimate(n, det);
  const double bound = kOrient3dBoundB * permanent;
  return exact || out > bound || -out > bound;
}

// insphere by stage B; false if undecided.
bool insphere(const double* a, const double* b, const double* c, const double* d, const double* e,
              double permanent, double& out) {
  double p[4][3];
  const double* q[4] = {a, b, c, d};
  bool exact = true;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) exact = exact_diff(q[i][k], e[k], p[i][k]) && exact;
  const double *ae = p[0], *be = p[1], *ce = p[2], *de = p[3];
  double ab[4], bc[4], cd[4], da[4], ac[4], bd[4];
  int nab = det2(ae[0], be[1], be[0], ae[1], ab);
  int nbc = det2(be[0], ce[1], ce[0], be[1], bc);
  int ncd = det2(ce[0], de[1], de[0], ce[1], cd);
  int nda = det2(de[0], ae[1], ae[0], de[1], da);
  int nac = det2(ae[0], ce[1], ce[0], ae[1], ac);
  int nbd = det2(be[0], de[1], de[0], be[1], bd);
  // abc = aez bc - bez ac + cez ab, and so on (as in the fast stage).
  double abc[24], bcd[24], cda[24], dab[24];
  int nabc = combo3(ae[2], nbc, bc, -be[2], nac, ac, ce[2], nab, ab, abc);
  int nbcd = combo3(be[2], ncd, cd, -ce[2], nbd, bd, de[2], nbc, bc, bcd);
  int ncda = combo3(ce[2], nda, da, de[2], nac, ac, ae[2], ncd, cd, cda);
  int ndab = combo3(de[2], nab, ab, ae[2], nbd, bd, be[2], nda, da, dab);
  auto lift = [](const double* v, double* h) {
    double s[2][2], t[4];
    two_product(v[0], v[0], s[0][1], s[0][0]);
    two_product(v[1], v[1], s[1][1], s[1][0]);
    double x[2], y[2], z[2];
    int xl = 0, yl = 0, zl = 0;
    for (double w : {s[0][0], s[0][1]})
      if (w != 0) x[xl++] = w;
    for (double w : {s[1][0], s[1][1]})
      if (w != 0) y[yl++] = w;
    double z1, z0;
    two_product(v[2], v[2], z1, z0);
    for (double w : {z0, z1})
      if (w != 0) z[zl++] = w;
    int tl = sum(xl, x, yl, y, t);
    return sum(tl, t, zl, z, h);
  };
  double la[6], lb[6], lc[6], ld[6];
  int nla = lift(ae, la), nlb = lift(be, lb), nlc = lift(ce, lc), nld = lift(de, ld);
  // det = (dlift abc - clift dab) + (blift cda - alift bcd)
  for (int i = 0; i < nlc; ++i) lc[i] = -lc[i];
  for (int i = 0; i < nla; ++i) la[i] = -la[i];
  double t1[288], t2[288], t3[288], t4[288], s1[576], s2[576], det[1152];
  int n1 = product(nld, ld, nabc, abc, t1);
  int n2 = product(nlc, lc, ndab, dab, t2);
  int n3 = product(nlb, lb, ncda, cda, t3);
  int n4 = product(nla, la, nbcd, bcd, t4);
  int m1 = sum(n1, t1, n2, t2, s1);
  int m2 = sum(n3, t3, n4, t4, s2);
  int n = sum(m1, s1, m2, s2, det);
  out = estimate(n, det);
  const double bound = kInsphereBoundB * permanent;
  return exact || out > bound || -out > bound;
}

}  // namespace fixed

}  // namespace

double orient2d(const double* a, const double* b, const double* c) {
  double detleft = (a[0] - c[0]) * (b[1] - c[1]);
  double detright = (a[1] - c[1]) * (b[0] - c[0]);
  double det = detleft - detright;
  double bound = kOrient2dBound * (std::fabs(detleft) + std::fabs(detright));
  if (det > bound || -det > bound) return det;
  return orient2d_exact(a, b, c);
}

double incircle(const double* a, const double* b, const double* c, const double* d) {
  double adx = a[0] - d[0], ady = a[1] - d[1];
  double bdx = b[0] - d[0], bdy = b[1] - d[1];
  double cdx = c[0] - d[0], cdy = c[1] - d[1];
  double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  double cdxady = cdx * ady, adxcdy = adx * cdy;
  double adxbdy = adx * bdy, bdxady = bdx * ady;
  double alift = adx * adx + ady * ady;
  double blift = bdx * bdx + bdy * bdy;
  double clift = cdx * cdx + cdy * cdy;
  double det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
  double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * alift +
                     (std::fabs(cdxady) + std::fabs(adxcdy)) * blift +
                     (std::fabs(adxbdy) + std::fabs(bdxady)) * clift;
  double bound = kIncircleBound * permanent;
  if (det > bound || -det > bound) return det;
  return incircle_exact(a, b, c, d);
}

double orient3d(const double* a, const double* b, const double* c, const double* d) {
  double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  double cdxady = cdx * ady, adxcdy = adx * cdy;
  double adxbdy = adx * bdy, bdxady = bdx * ady;
  double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * std::fabs(adz) +
                     (std::fabs(cdxady) + std::fabs(adxcdy)) * std::fabs(bdz) +
                     (std::fabs(adxbdy) + std::fabs(bdxady)) * std::fabs(cdz);
  double bound = kOrient3dBound * permanent;
  if (det > bound || -det > bound) return det;
  double exact;
  if (fixed::orient3d(a, b, c, d, permanent, exact)) return exact;
  return orient3d_exact(a, b, c, d);
}

double insphere(const double* a, const double* b, const double* c, const double* d,
                const double* e) {
  double aex = a[0] - e[0], aey = a[1] - e[1], aez = a[2] - e[2];
  double bex = b[0] - e[0], bey = b[1] - e[1], bez = b[2] - e[2];
  double cex = c[0] - e[0], cey = c[1] - e[1], cez = c[2] - e[2];
  double dex = d[0] - e[0], dey = d[1] - e[1], dez = d[2] - e[2];
  double aexbey = aex * bey, bexaey = bex * aey, ab = aexbey - bexaey;
  double bexcey = bex * cey, cexbey = cex * bey, bc = bexcey - cexbey;
  double cexdey = cex * dey, dexcey = dex * cey, cd = cexdey - dexcey;
  double dexaey = dex * aey, aexdey = aex * dey, da = dexaey - aexdey;
  double aexcey = aex * cey, cexaey = cex * aey, ac = aexcey - cexaey;
  double bexdey = bex * dey, dexbey = dex * bey, bd = bexdey - dexbey;
  double abc = aez * bc - bez * ac + cez * ab;
  double bcd = bez * cd - cez * bd + dez * bc;
  double cda = cez * da + dez * ac + aez * cd;
  double dab = dez * ab + aez * bd + bez * da;
  double alift = aex * aex + aey * aey + aez * aez;
  double blift = bex * bex + bey * bey + bez * bez;
  double clift = cex * cex + cey * cey + cez * cez;
  double dlift = dex * dex + dey * dey + dez * dez;
  double det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
  double az = std::fabs(aez), bz = std::fabs(bez), cz = std::fabs(cez), dz = std::fabs(dez);
  double abp = std::fabs(aexbey) + std::fabs(bexaey);
  double bcp = std::fabs(bexcey) + std::fabs(cexbey);
  double cdp = std::fabs(cexdey) + std::fabs(dexcey);
  double dap = std::fabs(dexaey) + std::fabs(aexdey);
  double acp = std::fabs(aexcey) + std::fabs(cexaey);
  double bdp = std::fabs(bexdey) + std::fabs(dexbey);
  double permanent =
      (cdp * bz + bdp * cz + bcp * dz) * alift + (dap * cz + acp * dz + cdp * az) * blift +
      (abp * dz + bdp * az + dap * bz) * clift + (bcp * az + acp * bz + abp * cz) * dlift;
  double bound = kInsphereBound * permanent;
  if (det > bound || -det > bound) return det;
  double exact;
  if (fixed::insphere(a, b, c, d, e, permanent, exact)) return exact;
  return insphere_exact(a, b, c, d, e);
}

int insphere_sos(const double* a, const double* b, const double* c, const double* d,
                 const double* e, int64_t ia, int64_t ib, int64_t ic, int64_t id, int64_t ie) {
  double det = insphere(a, b, c, d, e);
  if (det != 0) return det > 0 ? 1 : -1;
  // insphere(a, b, c, d, e) is the 5x5 determinant with rows (p, |p|^2, 1),
  // p = a..e. It is linear in the lift column, so raising row r's lift by
  // eps_r adds eps_r * (-1)^(r + 4) * det[(q, 1) for the other rows q] =
  // eps_r * (-1)^r * orient3d(others in order) (rows r = 1..5). The raises
  // are ordered by index: the first nonzero coefficient, from the largest
  // index down, decides.
  const double* p[5] = {a, b, c, d, e};
  int64_t idx[5] = {ia, ib, ic, id, ie};
  int order[5] = {0, 1, 2, 3, 4};
  for (int i = 1; i < 5; ++i)  // insertion sort, decreasing index
    for (int j = i; j > 0 && idx[order[j]] > idx[order[j - 1]]; --j) {
      int t = order[j];
      order[j] = order[j - 1];
      order[j - 1] = t;
    }
  for (int k = 0; k < 5; ++k) {
    int r = order[k];  // 0-based row
    const double* q[4];
    for (int i = 0, n = 0; i < 5; ++i)
      if (i != r) q[n++] = p[i];
    double o = orient3d(q[0], q[1], q[2], q[3]);
    if (o == 0) continue;
    // (-1)^(r + 1) with 1-based row r + 1.
    int s = (r % 2 == 0) ? -1 : 1;
    return o > 0 ? s : -s;
  }
  return 0;
}

}  // namespace vm
