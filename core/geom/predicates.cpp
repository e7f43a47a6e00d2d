// Filtered exact predicates (Shewchuk 1997). Fast path: the determinant in
// doubles, accepted when its magnitude exceeds the published forward error
// bound (ccwerrboundA, iccerrboundA, o3derrboundA, isperrboundA) times the
// permanent. Otherwise, for orient3d and insphere, stage D: the same
// formula in double-word arithmetic on the exact differences (below).
// Otherwise stage B: the same determinant of the rounded
// differences in expansion arithmetic on fixed arrays, decisive when the
// differences are exact or its value clears stage B's bound. Otherwise the
// determinant of the coordinates themselves, exactly, in expansion
// arithmetic on fixed arrays (no allocation); its estimate has the exact
// sign.
#include "core/geom/predicates.h"

#include <algorithm>
#include <cmath>

#include "core/geom/error_free.h"

namespace vm {
namespace {

constexpr double kEps = 0x1p-53;  // half an ulp of 1
constexpr double kOrient2dBound = (3.0 + 16.0 * kEps) * kEps;
constexpr double kIncircleBound = (10.0 + 96.0 * kEps) * kEps;
constexpr double kOrient3dBound = (7.0 + 56.0 * kEps) * kEps;
constexpr double kInsphereBound = (16.0 + 224.0 * kEps) * kEps;

// Stage D (double-word): between the fast stage and stage B. The
// coordinate differences are exact double-words (Two-Sum), and the fast
// stage's formula is evaluated in double-word arithmetic: addition by
// Joldes, Muller and Popescu's AccurateDWPlusDW ("Tight and rigorous error
// bounds for basic building blocks of double-word arithmetic", ACM TOMS
// 44, 2017, Algorithm 6: relative error <= 3u^2 + 13u^3) and
// multiplication by Dekker's product with the cross terms (CRlibm's Mul22,
// relative error < 2^-102 = 16u^2), u = 2^-53. Every operation is thus
// exact up to a factor (1 + d), |d| <= 16u^2, and a formula of depth k
// (operations on the longest path from a difference to the result) is off
// by at most gamma_k = k 16u^2 / (1 - k 16u^2) times its permanent (the
// same formula on absolute values), as in Shewchuk's analysis of the fast
// stage (Higham, "Accuracy and Stability of Numerical Algorithms", 3.1).
// insphere has depth 8 (2x2 minor 2, 3x3 minor 5, times the lift 6, two
// sums 8): gamma_8 < 2^-98.9; orient3d depth 5. The fast stage's
// permanent, from rounded differences and rounded operations on
// nonnegative terms, is at least (1 - 16u) times the exact one. So
// |value| > 2^-96 * permanent decides, with a margin of 7x. Underflow
// adds at most a few 2^-1074 per operation, times cofactors below
// 2^10 m^4 where m is the largest difference; with m <= 2^100 and the
// permanent >= 2^-500 that stays under 2^-600, far below the margin. Out
// of that range, or when the value is within 2^-96 of the permanent
// (exact ties, such as cospherical integer points), stage B and the exact
// path decide. Points on a sphere or a plane up to their coordinates'
// rounding, which the fast stage cannot decide, are decided here instead
// of in the expansion arithmetic, which is tens of times slower.
namespace dw {

using exact::two_product;
using exact::two_sum;

struct DW {
  double hi, lo;
};

// x + y = s + e exactly, given |a| >= |b| or a = 0 (Fast-Two-Sum).
inline void fast_two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  e = b - (s - a);
}

inline DW diff(double a, double b) {
  DW r;
  two_sum(a, -b, r.hi, r.lo);
  return r;
}

inline DW add(DW x, DW y) {
  double sh, sl, th, tl, vh, vl;
  two_sum(x.hi, y.hi, sh, sl);
  two_sum(x.lo, y.lo, th, tl);
  fast_two_sum(sh, sl + th, vh, vl);
  DW r;
  fast_two_sum(vh, tl + vl, r.hi, r.lo);
  return r;
}

inline DW sub(DW x, DW y) { return add(x, DW{-y.hi, -y.lo}); }

inline DW mul(DW x, DW y) {
  double ph, pl;
  two_product(x.hi, y.hi, ph, pl);
  pl += x.hi * y.lo + x.lo * y.hi;
  DW r;
  fast_two_sum(ph, pl, r.hi, r.lo);
  return r;
}

constexpr double kBound = 0x1p-96;
constexpr double kMaxDiff = 0x1p100;
constexpr double kMinPermanent = 0x1p-500;

// The largest |d.hi|.
template <size_t N>
double largest(const DW (&d)[N][3]) {
  double m = 0;
  for (const auto& p : d)
    for (const DW& x : p) m = std::max(m, std::fabs(x.hi));
  return m;
}

// orient3d in double-words; false if undecided.
bool orient3d(const double* a, const double* b, const double* c, const double* d, double permanent,
              double& out) {
  if (!(permanent >= kMinPermanent)) return false;
  DW p[3][3];
  const double* q[3] = {a, b, c};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) p[i][k] = diff(q[i][k], d[k]);
  if (!(largest(p) <= kMaxDiff)) return false;
  const DW *ad = p[0], *bd = p[1], *cd = p[2];
  const DW bc = sub(mul(bd[0], cd[1]), mul(cd[0], bd[1]));
  const DW ca = sub(mul(cd[0], ad[1]), mul(ad[0], cd[1]));
  const DW ab = sub(mul(ad[0], bd[1]), mul(bd[0], ad[1]));
  const DW det = add(add(mul(ad[2], bc), mul(bd[2], ca)), mul(cd[2], ab));
  out = det.hi;
  const double bound = kBound * permanent;
  return out > bound || -out > bound;
}

// insphere in double-words; false if undecided.
bool insphere(const double* a, const double* b, const double* c, const double* d, const double* e,
              double permanent, double& out) {
  if (!(permanent >= kMinPermanent)) return false;
  DW p[4][3];
  const double* q[4] = {a, b, c, d};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) p[i][k] = diff(q[i][k], e[k]);
  if (!(largest(p) <= kMaxDiff)) return false;
  const DW *ae = p[0], *be = p[1], *ce = p[2], *de = p[3];
  const DW ab = sub(mul(ae[0], be[1]), mul(be[0], ae[1]));
  const DW bc = sub(mul(be[0], ce[1]), mul(ce[0], be[1]));
  const DW cd = sub(mul(ce[0], de[1]), mul(de[0], ce[1]));
  const DW da = sub(mul(de[0], ae[1]), mul(ae[0], de[1]));
  const DW ac = sub(mul(ae[0], ce[1]), mul(ce[0], ae[1]));
  const DW bd = sub(mul(be[0], de[1]), mul(de[0], be[1]));
  const DW abc = add(sub(mul(ae[2], bc), mul(be[2], ac)), mul(ce[2], ab));
  const DW bcd = add(sub(mul(be[2], cd), mul(ce[2], bd)), mul(de[2], bc));
  const DW cda = add(add(mul(ce[2], da), mul(de[2], ac)), mul(ae[2], cd));
  const DW dab = add(add(mul(de[2], ab), mul(ae[2], bd)), mul(be[2], da));
  auto lift = [](const DW* v) {
    return add(add(mul(v[0], v[0]), mul(v[1], v[1])), mul(v[2], v[2]));
  };
  const DW det =
      add(sub(mul(lift(de), abc), mul(lift(ce), dab)), sub(mul(lift(be), cda), mul(lift(ae), bcd)));
  out = det.hi;
  const double bound = kBound * permanent;
  return out > bound || -out > bound;
}

}  // namespace dw

// Shewchuk's adaptive stage B on fixed-size arrays (no allocation): the
// determinant of the rounded coordinate differences, evaluated exactly in
// expansion arithmetic of bounded length. When every difference is exact
// (common for nearby points: Sterbenz's lemma) it is the exact determinant;
// otherwise it differs from it by at most errboundB * permanent (Shewchuk
// 1997, o3derrboundB, isperrboundB), which decides most of the remaining
// cases. What stage B cannot decide goes to the exact path below.
namespace fixed {

using exact::two_product;
using exact::two_sum;

inline bool exact_diff(double a, double b, double& d) {
  double y;
  two_sum(a, -b, d, y);
  return y == 0;
}

// h = e + f (Shewchuk's Theorem 13 with Two-Sum throughout, zero
// elimination): the terms merged by magnitude into h, then one Two-Sum
// sweep in place (it writes term m <= k - 1 while reading term k). e, f
// increasing magnitude, nonoverlapping; h holds elen + flen terms and
// aliases neither.
int sum(int elen, const double* e, int flen, const double* f, double* h) {
  int i = 0, j = 0, n = 0;
  while (i < elen && j < flen) h[n++] = std::fabs(e[i]) <= std::fabs(f[j]) ? e[i++] : f[j++];
  while (i < elen) h[n++] = e[i++];
  while (j < flen) h[n++] = f[j++];
  if (n == 0) return 0;
  int m = 0;
  double q = h[0];
  for (int k = 1; k < n; ++k) {
    double qn, hh;
    two_sum(q, h[k], qn, hh);
    if (hh != 0) h[m++] = hh;
    q = qn;
  }
  if (q != 0 || m == 0) h[m++] = q;
  return m;
}

// Compresses expansion e (n terms, increasing) in place to as few terms as
// its value needs (Shewchuk's Compress: a Two-Sum sweep down from the
// largest term, then one up); returns the new length. Long expansions
// shrink to a few terms, which keeps the products below short.
int compress(int n, double* e) {
  if (n < 2) return n;
  int bottom = n - 1;
  double q = e[bottom];
  for (int i = n - 2; i >= 0; --i) {
    double x, y;
    two_sum(q, e[i], x, y);
    if (y != 0) {
      e[bottom--] = x;
      q = y;
    } else {
      q = x;
    }
  }
  e[bottom] = q;
  int top = 0;
  for (int i = bottom + 1; i < n; ++i) {
    double x, y;
    two_sum(e[i], q, x, y);
    if (y != 0) e[top++] = y;
    q = x;
  }
  e[top++] = q;
  return top;
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

// h = e * f: f's terms scale e one at a time, summed. h and scratch hold
// 2 * elen * flen terms each, part 2 * elen; none aliases e or f.
int product(int elen, const double* e, int flen, const double* f, double* h, double* scratch,
            double* part) {
  int alen = 0;
  double *acc = h, *next = scratch;
  for (int i = 0; i < flen; ++i) {
    const int plen = scale(elen, e, f[i], part);
    alen = sum(alen, acc, plen, part, next);
    std::swap(acc, next);
  }
  if (acc != h) std::copy(acc, acc + alen, h);
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

// |p|^2 over the first `dim` coordinates (<= 2 * dim terms).
int lift(int dim, const double* p, double* h) {
  double acc[6], sq[2], tmp[6];
  int n = 0;
  for (int k = 0; k < dim; ++k) {
    double hi, lo;
    two_product(p[k], p[k], hi, lo);
    int sl = 0;
    if (lo != 0) sq[sl++] = lo;
    if (hi != 0) sq[sl++] = hi;
    n = sum(n, acc, sl, sq, tmp);
    std::copy(tmp, tmp + n, acc);
  }
  std::copy(acc, acc + n, h);
  return n;
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
  int nabc = compress(combo3(ae[2], nbc, bc, -be[2], nac, ac, ce[2], nab, ab, abc), abc);
  int nbcd = compress(combo3(be[2], ncd, cd, -ce[2], nbd, bd, de[2], nbc, bc, bcd), bcd);
  int ncda = compress(combo3(ce[2], nda, da, de[2], nac, ac, ae[2], ncd, cd, cda), cda);
  int ndab = compress(combo3(de[2], nab, ab, ae[2], nbd, bd, be[2], nda, da, dab), dab);
  double la[6], lb[6], lc[6], ld[6];
  int nla = lift(3, ae, la), nlb = lift(3, be, lb), nlc = lift(3, ce, lc), nld = lift(3, de, ld);
  // det = (dlift abc - clift dab) + (blift cda - alift bcd)
  for (int i = 0; i < nlc; ++i) lc[i] = -lc[i];
  for (int i = 0; i < nla; ++i) la[i] = -la[i];
  double t1[288], t2[288], t3[288], t4[288], s1[576], s2[576], det[1152], scratch[288], part[48];
  int n1 = product(nabc, abc, nld, ld, t1, scratch, part);
  int n2 = product(ndab, dab, nlc, lc, t2, scratch, part);
  int n3 = product(ncda, cda, nlb, lb, t3, scratch, part);
  int n4 = product(nbcd, bcd, nla, la, t4, scratch, part);
  int m1 = sum(n1, t1, n2, t2, s1);
  int m2 = sum(n3, t3, n4, t4, s2);
  int n = sum(m1, s1, m2, s2, det);
  out = estimate(n, det);
  const double bound = kInsphereBoundB * permanent;
  return exact || out > bound || -out > bound;
}

// ---- Exact determinants from the coordinates themselves (Shewchuk 1997,
// the "exact" predicates): no difference is rounded, so every minor below
// is an exact expansion of bounded length and the arrays need no
// allocation. The last resort, when stage B cannot decide.

// The xy minor x_i y_j - x_j y_i (<= 4 terms).
int minor2(const double* i, const double* j, double* h) { return det2(i[0], j[1], j[0], i[1], h); }

// -e.
void negate(int n, double* e) {
  for (int k = 0; k < n; ++k) e[k] = -e[k];
}

// s1 e1 - s2 e2 + s3 e3 - s4 e4 for expansions e (the alternating
// cofactor sum of a determinant), into h; term counts add up.
int alternate(int n1, double* e1, int n2, double* e2, int n3, double* e3, int n4, double* e4,
              double* h, double* scratch) {
  negate(n2, e2);
  negate(n4, e4);
  const int a = sum(n1, e1, n2, e2, h);
  const int b = sum(n3, e3, n4, e4, h + a);
  const int n = sum(a, h, b, h + a, scratch);
  std::copy(scratch, scratch + n, h);
  negate(n2, e2);
  negate(n4, e4);
  return n;
}

// det[(p, 1)] of three 2D points, <= 12 terms: m_bc - m_ac + m_ab.
int orient2d_terms(const double* a, const double* b, const double* c, double* h) {
  double bc[4], ac[4], ab[4], t[8];
  const int nbc = minor2(b, c, bc), nac = minor2(a, c, ac), nab = minor2(a, b, ab);
  negate(nac, ac);
  const int nt = sum(nbc, bc, nac, ac, t);
  return sum(nt, t, nab, ab, h);
}

double orient2d_exact(const double* a, const double* b, const double* c) {
  double det[12];
  return estimate(orient2d_terms(a, b, c, det), det);
}

// Sum over rows r of (-1)^r lift_r * minor_r, the cofactor expansion of a
// determinant along its lift column (rows 0-based, the first one positive):
// lift[r] (nl[r] terms) times minor[r] (nm[r] terms), r < rows.
template <int kRows, int kLift, int kMinor>
double lift_expansion(const double (*lifts)[kLift], const int* nl, const double (*minors)[kMinor],
                      const int* nm) {
  constexpr int kTerm = 2 * kLift * kMinor;
  double term[kTerm], scratch[kTerm], part[2 * kMinor];
  double acc[kRows * kTerm], next[kRows * kTerm];
  int alen = 0;
  for (int r = 0; r < kRows; ++r) {
    int n = compress(product(nm[r], minors[r], nl[r], lifts[r], term, scratch, part), term);
    if (r % 2) negate(n, term);
    alen = compress(sum(alen, acc, n, term, next), next);
    std::copy(next, next + alen, acc);
  }
  return estimate(alen, acc);
}

double incircle_exact(const double* a, const double* b, const double* c, const double* d) {
  // det[(p, |p|^2, 1)]: along the lift column, row r's minor is
  // orient2d of the other rows, with sign (-1)^(r + 3) (1-based r).
  const double* p[4] = {a, b, c, d};
  double lifts[4][4], minors[4][12];
  int nl[4], nm[4];
  for (int r = 0; r < 4; ++r) {
    const double* q[3];
    for (int i = 0, n = 0; i < 4; ++i)
      if (i != r) q[n++] = p[i];
    nl[r] = lift(2, p[r], lifts[r]);
    nm[r] = orient2d_terms(q[0], q[1], q[2], minors[r]);
  }
  return lift_expansion<4, 4, 12>(lifts, nl, minors, nm);
}

// The xyz minors z_i m_jk - z_j m_ik + z_k m_ij (<= 24 terms) of every
// triple i < j < k of n <= 5 points, indexed by the triple's bit mask.
struct TripleMinors {
  double m[32][24];
  int n[32];
};

void triple_minors(int n, const double* const* p, TripleMinors& out) {
  double m2[5][5][4];
  int n2[5][5];
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) n2[i][j] = minor2(p[i], p[j], m2[i][j]);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k) {
        const int t = 1 << i | 1 << j | 1 << k;
        out.n[t] = compress(combo3(p[i][2], n2[j][k], m2[j][k], -p[j][2], n2[i][k], m2[i][k],
                                   p[k][2], n2[i][j], m2[i][j], out.m[t]),
                            out.m[t]);
      }
}

// det[(q, 1)] (<= 96 terms) of the four points in mask `four`, in
// increasing order q0..q3: along the ones column,
// -M(q1 q2 q3) + M(q0 q2 q3) - M(q0 q1 q3) + M(q0 q1 q2).
int orient3d_terms(TripleMinors& m, int four, double* h) {
  int omit[4], c = 0;
  for (int i = 0; i < 5; ++i)
    if (four >> i & 1) omit[c++] = four & ~(1 << i);
  double scratch[96];
  return compress(alternate(m.n[omit[1]], m.m[omit[1]], m.n[omit[2]], m.m[omit[2]], m.n[omit[3]],
                            m.m[omit[3]], m.n[omit[0]], m.m[omit[0]], h, scratch),
                  h);
}

double orient3d_exact(const double* a, const double* b, const double* c, const double* d) {
  const double* p[4] = {a, b, c, d};
  TripleMinors m;
  triple_minors(4, p, m);
  double det[96];
  return estimate(orient3d_terms(m, 0b1111, det), det);
}

double insphere_exact(const double* a, const double* b, const double* c, const double* d,
                      const double* e) {
  // det[(p, |p|^2, 1)]: along the lift column, row r's minor is
  // orient3d of the other rows, with sign (-1)^(r + 4) (1-based r): the
  // first row's is negative.
  const double* p[5] = {a, b, c, d, e};
  TripleMinors m;
  triple_minors(5, p, m);
  double lifts[5][6], minors[5][96];
  int nl[5], nm[5];
  for (int r = 0; r < 5; ++r) {
    nl[r] = lift(3, p[r], lifts[r]);
    nm[r] = orient3d_terms(m, 0b11111 & ~(1 << r), minors[r]);
  }
  return -lift_expansion<5, 6, 96>(lifts, nl, minors, nm);
}

}  // namespace fixed

}  // namespace

double orient2d(const double* a, const double* b, const double* c) {
  double detleft = (a[0] - c[0]) * (b[1] - c[1]);
  double detright = (a[1] - c[1]) * (b[0] - c[0]);
  double det = detleft - detright;
  double bound = kOrient2dBound * (std::fabs(detleft) + std::fabs(detright));
  if (det > bound || -det > bound) return det;
  return fixed::orient2d_exact(a, b, c);
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
  return fixed::incircle_exact(a, b, c, d);
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
  if (dw::orient3d(a, b, c, d, permanent, exact)) return exact;
  if (fixed::orient3d(a, b, c, d, permanent, exact)) return exact;
  return fixed::orient3d_exact(a, b, c, d);
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
  if (dw::insphere(a, b, c, d, e, permanent, exact)) return exact;
  if (fixed::insphere(a, b, c, d, e, permanent, exact)) return exact;
  return fixed::insphere_exact(a, b, c, d, e);
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
