// Filtered exact predicates (Shewchuk 1997). Fast path: the determinant in
// doubles, accepted when its magnitude exceeds the published forward error
// bound (ccwerrboundA, iccerrboundA, o3derrboundA, isperrboundA) times the
// permanent. Otherwise the same determinant (expanded about the last point)
// is evaluated exactly in expansion arithmetic; its estimate has the exact
// sign.
#include "core/geom/predicates.h"

#include <cmath>

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
