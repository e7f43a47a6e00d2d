#include "core/geom/predicates.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "tests/support/expansion_reference.h"

namespace vm {
namespace {

using i128 = __int128;

int sign(double x) { return (x > 0) - (x < 0); }
int sign(i128 x) { return (x > 0) - (x < 0); }

i128 orient2d_ref(const i128* a, const i128* b, const i128* c) {
  return (a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0]);
}

i128 incircle_ref(const i128* a, const i128* b, const i128* c, const i128* d) {
  i128 adx = a[0] - d[0], ady = a[1] - d[1], bdx = b[0] - d[0], bdy = b[1] - d[1];
  i128 cdx = c[0] - d[0], cdy = c[1] - d[1];
  return (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) +
         (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
         (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
}

i128 det3_ref(const i128* a, const i128* b, const i128* c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
}

i128 orient3d_ref(const i128* a, const i128* b, const i128* c, const i128* d) {
  i128 ad[3], bd[3], cd[3];
  for (int k = 0; k < 3; ++k) ad[k] = a[k] - d[k], bd[k] = b[k] - d[k], cd[k] = c[k] - d[k];
  return det3_ref(ad, bd, cd);
}

i128 insphere_ref(const i128* a, const i128* b, const i128* c, const i128* d, const i128* e) {
  i128 p[4][3];
  const i128* pts[4] = {a, b, c, d};
  i128 lift[4];
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 3; ++k) p[i][k] = pts[i][k] - e[k];
    lift[i] = p[i][0] * p[i][0] + p[i][1] * p[i][1] + p[i][2] * p[i][2];
  }
  return lift[3] * det3_ref(p[0], p[1], p[2]) - lift[2] * det3_ref(p[0], p[1], p[3]) +
         lift[1] * det3_ref(p[0], p[2], p[3]) - lift[0] * det3_ref(p[1], p[2], p[3]);
}

TEST(Predicates, RandomIntegerPointsMatchExactArithmetic) {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int64_t> small(-20, 20), big(-(1 << 20), 1 << 20);
  for (int it = 0; it < 20000; ++it) {
    auto& dist = it % 2 ? small : big;  // small coordinates are often degenerate
    double p[5][3];
    i128 q[5][3];
    for (int i = 0; i < 5; ++i)
      for (int k = 0; k < 3; ++k) q[i][k] = dist(rng), p[i][k] = double(q[i][k]);
    ASSERT_EQ(sign(orient2d(p[0], p[1], p[2])), sign(orient2d_ref(q[0], q[1], q[2])));
    ASSERT_EQ(sign(incircle(p[0], p[1], p[2], p[3])), sign(incircle_ref(q[0], q[1], q[2], q[3])));
    ASSERT_EQ(sign(orient3d(p[0], p[1], p[2], p[3])), sign(orient3d_ref(q[0], q[1], q[2], q[3])));
    ASSERT_EQ(sign(insphere(p[0], p[1], p[2], p[3], p[4])),
              sign(insphere_ref(q[0], q[1], q[2], q[3], q[4])));
  }
}

TEST(Predicates, NearlyDegenerateRealPointsMatchAnIndependentExactEvaluation) {
  // Points nearly on one circle / sphere / line / plane, with coordinates
  // across binades (so coordinate differences round and the filters and
  // stage B often cannot decide): the signs must be those of a separate
  // exact evaluation (tests/support/expansion_reference.h).
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(-1, 1), angle(0, 6.283185307179586);
  int nonzero = 0;
  for (int it = 0; it < 4000; ++it) {
    const double scale = std::pow(10.0, double(it % 7) - 3);
    const double c[3] = {u(rng) * scale, u(rng) * scale, u(rng) * scale};
    const double r = scale * (0.5 + 0.5 * std::fabs(u(rng)));
    double s[5][3], f[5][3];  // on a sphere (z = c[2] gives a circle); on a plane
    for (int i = 0; i < 5; ++i) {
      const double t = angle(rng), z = u(rng);
      const double h = std::sqrt(1 - z * z);
      s[i][0] = c[0] + r * h * std::cos(t), s[i][1] = c[1] + r * h * std::sin(t);
      s[i][2] = c[2] + r * z;
      const double a = u(rng), b = u(rng);
      for (int k = 0; k < 3; ++k)
        f[i][k] = i < 3 ? s[i][k] : a * s[0][k] + b * s[1][k] + (1 - a - b) * s[2][k];
    }
    double ring[4][2];  // on the circle of the sphere's equator
    for (auto& q : ring) {
      const double t = angle(rng);
      q[0] = c[0] + r * std::cos(t), q[1] = c[1] + r * std::sin(t);
    }
    ASSERT_EQ(sign(insphere(s[0], s[1], s[2], s[3], s[4])),
              test::insphere_sign(s[0], s[1], s[2], s[3], s[4]))
        << it;
    ASSERT_EQ(sign(orient3d(f[0], f[1], f[2], f[3])), test::orient3d_sign(f[0], f[1], f[2], f[3]))
        << it;
    ASSERT_EQ(sign(orient3d(f[4], f[1], f[3], f[2])), test::orient3d_sign(f[4], f[1], f[3], f[2]))
        << it;
    ASSERT_EQ(sign(incircle(ring[0], ring[1], ring[2], ring[3])),
              test::incircle_sign(ring[0], ring[1], ring[2], ring[3]))
        << it;
    double line[3][2] = {{f[0][0], f[0][1]}, {f[1][0], f[1][1]}, {0, 0}};
    const double a = u(rng);
    for (int k = 0; k < 2; ++k) line[2][k] = a * line[0][k] + (1 - a) * line[1][k];
    ASSERT_EQ(sign(orient2d(line[0], line[1], line[2])),
              test::orient2d_sign(line[0], line[1], line[2]))
        << it;
    nonzero += test::insphere_sign(s[0], s[1], s[2], s[3], s[4]) != 0;
  }
  EXPECT_GT(nonzero, 3000);  // rounding moves the points off the sphere
}

TEST(Predicates, NearlyCosphericalAndCoplanarSetsAcrossScalesMatchExactSigns) {
  // The double-word stage's territory: points on a sphere or a plane up to
  // their coordinates' rounding, moved off it by 0-8 ulps, at scales
  // 1e-6..1e6 and centers far from the origin (differences round). Every
  // sign, through insphere, insphere_fast and orient3d, is the exact one.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> ulps(-8, 8);
  int signs[3] = {0, 0, 0};
  for (int it = 0; it < 20000; ++it) {
    const double scale = std::pow(10.0, double(it % 13) - 6);
    const double offset = it % 3 == 0 ? 0 : std::pow(10.0, double(it % 5)) * scale;
    const double c[3] = {offset + u(rng) * scale, u(rng) * scale, -offset};
    double s[5][3], f[4][3];
    for (int i = 0; i < 5; ++i) {
      double n[3] = {u(rng), u(rng), u(rng)};
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (int k = 0; k < 3; ++k) {
        s[i][k] = c[k] + scale * n[k] / len;
        for (int m = ulps(rng) * (i == 4); m != 0; m += m > 0 ? -1 : 1)
          s[i][k] = std::nextafter(s[i][k], m > 0 ? HUGE_VAL : -HUGE_VAL);
      }
    }
    for (int i = 0; i < 4; ++i) {
      const double a = u(rng), b = u(rng);
      for (int k = 0; k < 3; ++k)
        f[i][k] = i < 3 ? s[i][k] : a * s[0][k] + b * s[1][k] + (1 - a - b) * s[2][k];
    }
    const int want = test::insphere_sign(s[0], s[1], s[2], s[3], s[4]);
    ASSERT_EQ(sign(insphere(s[0], s[1], s[2], s[3], s[4])), want) << it;
    ASSERT_EQ(sign(insphere_fast(s[0], s[1], s[2], s[3], s[4])), want) << it;
    ASSERT_EQ(sign(orient3d(f[0], f[1], f[2], f[3])), test::orient3d_sign(f[0], f[1], f[2], f[3]))
        << it;
    ++signs[want + 1];
  }
  EXPECT_GT(signs[0], 5000);  // both sides of the sphere are exercised
  EXPECT_GT(signs[2], 5000);
}

TEST(Predicates, ExactTiesWithLargeIntegerCoordinatesAreZero) {
  // Points exactly on a sphere (Euler's parametrization: x = 2(mq + np),
  // y = 2(nq - mp), z = m^2 + n^2 - p^2 - q^2, r = m^2 + n^2 + p^2 + q^2)
  // or a plane, with integer coordinates up to 2^50: the differences are
  // exact but the products need more than two doubles, so the double-word
  // stage's value is not zero and it must leave the decision to the exact
  // stages, which give 0.
  std::mt19937_64 rng(8);
  std::uniform_int_distribution<int64_t> par(-(1 << 20), 1 << 20), off(-(1ll << 49), 1ll << 49);
  for (int it = 0; it < 2000; ++it) {
    const double c[3] = {double(off(rng)), double(off(rng)), double(off(rng))};
    const int64_t m = par(rng), n = par(rng), p = par(rng), r = par(rng);
    const double d[3] = {double(2 * (m * r + n * p)), double(2 * (n * r - m * p)),
                         double(m * m + n * n - p * p - r * r)};
    // Five points of that sphere: d with its coordinates permuted and
    // negated, which keeps |d|.
    const double on[5][3] = {{d[0], d[1], d[2]},
                             {-d[1], d[0], d[2]},
                             {d[2], -d[0], d[1]},
                             {-d[0], -d[2], -d[1]},
                             {d[1], d[2], -d[0]}};
    double s[5][3];
    for (int i = 0; i < 5; ++i)
      for (int k = 0; k < 3; ++k) s[i][k] = c[k] + on[i][k];
    ASSERT_EQ(test::insphere_sign(s[0], s[1], s[2], s[3], s[4]), 0) << it;
    ASSERT_EQ(insphere(s[0], s[1], s[2], s[3], s[4]), 0.0) << it;
    ASSERT_EQ(insphere_fast(s[0], s[1], s[2], s[3], s[4]), 0.0) << it;
    double f[4][3];
    const int64_t a = par(rng), b = par(rng);
    for (int k = 0; k < 3; ++k) {
      const double e1 = double(par(rng)) * 4096, e2 = double(par(rng)) * 4096;
      f[0][k] = c[k], f[1][k] = c[k] + e1, f[2][k] = c[k] + e2;
      f[3][k] = c[k] + double(a) * e1 / 4096 + double(b) * e2 / 4096;
    }
    ASSERT_EQ(test::orient3d_sign(f[0], f[1], f[2], f[3]), 0) << it;
    ASSERT_EQ(orient3d(f[0], f[1], f[2], f[3]), 0.0) << it;
  }
}

TEST(Predicates, FastInsphereSignsMatchExactArithmetic) {
  // insphere_fast with and without the static filter (a bound for the
  // box [-2^20, 2^20]^3), on general and on degenerate (small) points.
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int64_t> small(-6, 6), big(-(1 << 20), 1 << 20);
  const double bound = insphere_static_bound(double(1 << 21));
  for (int it = 0; it < 20000; ++it) {
    auto& dist = it % 2 ? small : big;
    double p[5][3];
    i128 q[5][3];
    for (int i = 0; i < 5; ++i)
      for (int k = 0; k < 3; ++k) q[i][k] = dist(rng), p[i][k] = double(q[i][k]);
    const int want = sign(insphere_ref(q[0], q[1], q[2], q[3], q[4]));
    ASSERT_EQ(sign(insphere_fast(p[0], p[1], p[2], p[3], p[4])), want) << it;
    ASSERT_EQ(sign(insphere_fast(p[0], p[1], p[2], p[3], p[4], bound)), want) << it;
  }
}

TEST(Predicates, FastInsphereStaticStageIsTheScalarFormulaToTheBit) {
  // The static stage runs two lanes at a time; each lane must perform the
  // scalar formula's operations in its order, so that every target (SSE2,
  // wasm, scalar) filters alike. A zero bound returns the stage's value.
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(-3, 3);
  for (int it = 0; it < 20000; ++it) {
    double p[5][3];
    for (auto& x : p)
      for (double& c : x) c = u(rng) * std::pow(10.0, double(it % 7) - 3);
    const double *a = p[0], *b = p[1], *c = p[2], *d = p[3], *e = p[4];
    const double aex = a[0] - e[0], aey = a[1] - e[1], aez = a[2] - e[2];
    const double bex = b[0] - e[0], bey = b[1] - e[1], bez = b[2] - e[2];
    const double cex = c[0] - e[0], cey = c[1] - e[1], cez = c[2] - e[2];
    const double dex = d[0] - e[0], dey = d[1] - e[1], dez = d[2] - e[2];
    const double ab = aex * bey - bex * aey, bc = bex * cey - cex * bey;
    const double cd = cex * dey - dex * cey, da = dex * aey - aex * dey;
    const double ac = aex * cey - cex * aey, bd = bex * dey - dex * bey;
    const double abc = aez * bc - bez * ac + cez * ab;
    const double bcd = bez * cd - cez * bd + dez * bc;
    const double cda = cez * da + dez * ac + aez * cd;
    const double dab = dez * ab + aez * bd + bez * da;
    const double alift = aex * aex + aey * aey + aez * aez;
    const double blift = bex * bex + bey * bey + bez * bez;
    const double clift = cex * cex + cey * cey + cez * cez;
    const double dlift = dex * dex + dey * dey + dez * dez;
    const double want = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
    ASSERT_NE(want, 0);
    const double got = insphere_fast(a, b, c, d, e, 0.0);
    ASSERT_EQ(std::memcmp(&got, &want, sizeof got), 0) << it << ": " << got << " " << want;
  }
}

TEST(Predicates, Orient2dOnANearlyCollinearUlpGrid) {
  // The classic failure of naive orient2d: points near the line y = x,
  // perturbed by a few ulps. Doubles in [0.5, 32) are integers times 2^-53,
  // so the exact reference fits in 128 bits.
  const double b[2] = {12, 12}, c[2] = {24, 24};
  auto scaled = [](double x) { return i128(std::ldexp(x, 53)); };
  int degenerate = 0, wrong_naive = 0;
  for (int i = 0; i < 64; ++i) {
    for (int j = 0; j < 64; ++j) {
      double a[2] = {0.5, 0.5};
      for (int k = 0; k < i; ++k) a[0] = std::nextafter(a[0], 1.0);
      for (int k = 0; k < j; ++k) a[1] = std::nextafter(a[1], 1.0);
      i128 qa[2] = {scaled(a[0]), scaled(a[1])}, qb[2] = {scaled(b[0]), scaled(b[1])},
           qc[2] = {scaled(c[0]), scaled(c[1])};
      int exact = sign(orient2d_ref(qa, qb, qc));
      ASSERT_EQ(sign(orient2d(a, b, c)), exact) << i << " " << j;
      ASSERT_EQ(sign(orient2d(b, c, a)), exact);
      ASSERT_EQ(sign(orient2d(b, a, c)), -exact);
      degenerate += exact == 0;
      double naive = (a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0]);
      wrong_naive += sign(naive) != exact;
    }
  }
  EXPECT_GT(degenerate, 0);
  EXPECT_GT(wrong_naive, 0) << "the grid does not exercise the exact path";
}

TEST(Predicates, CocircularAndCosphericalAreZero) {
  // Integer points on x^2 + y^2 = 25^2 and on a sphere of radius 3 (with
  // points (0,0,3), (2,2,1), ...), shifted off the origin.
  const double s = 1e6;
  double c1[][2] = {
      {7 + s, 24 + s}, {-24 + s, 7 + s}, {-20 + s, -15 + s}, {15 + s, -20 + s}, {25 + s, 0 + s}};
  EXPECT_EQ(incircle(c1[0], c1[1], c1[2], c1[3]), 0.0);
  EXPECT_EQ(incircle(c1[0], c1[1], c1[2], c1[4]), 0.0);
  double inside[2] = {1 + s, 1 + s}, outside[2] = {30 + s, 0 + s};
  EXPECT_GT(incircle(c1[0], c1[1], c1[2], inside), 0);  // 7,24 -> -24,7 -> -20,-15 is ccw
  EXPECT_LT(incircle(c1[0], c1[1], c1[2], outside), 0);
  double sp[][3] = {{0, 0, 3}, {2, 2, 1}, {-2, 1, 2}, {1, -2, -2}, {0, 3, 0}};
  for (auto& p : sp)
    for (double& x : p) x += 1000;
  EXPECT_EQ(insphere(sp[0], sp[1], sp[2], sp[3], sp[4]), 0.0);
  double center[3] = {1000, 1000, 1000};
  double o = orient3d(sp[0], sp[1], sp[2], sp[3]);
  ASSERT_NE(o, 0);
  EXPECT_EQ(sign(insphere(sp[0], sp[1], sp[2], sp[3], center)), sign(o));
}

TEST(Predicates, CoplanarAndCollinearAreZero) {
  double a[3] = {0.1, 0.2, 0.3}, b[3] = {1.1, 0.7, 0.3}, c[3] = {-3.3, 5.25, 0.3},
         d[3] = {7.5, -1.25, 0.3};
  EXPECT_EQ(orient3d(a, b, c, d), 0.0);
  double up[3] = {0.1, 0.2, 0.30000000000000004};
  EXPECT_NE(orient3d(a, b, c, up), 0.0);
  double p[2] = {0.1, 0.1}, q[2] = {0.3, 0.3}, r[2] = {0.7, 0.7};
  // 0.1, 0.3, 0.7 are not exactly on one line in binary; the sign must
  // agree with the exact determinant, which is tiny but non-zero or zero.
  auto scaled = [](double x) { return i128(std::ldexp(x, 60)); };
  i128 qp[2] = {scaled(p[0]), scaled(p[1])}, qq[2] = {scaled(q[0]), scaled(q[1])},
       qr[2] = {scaled(r[0]), scaled(r[1])};
  EXPECT_EQ(sign(orient2d(p, q, r)), sign(orient2d_ref(qp, qq, qr)));
}

// Reference for insphere_sos: the 5x5 lifting determinant (rows x, y, z,
// lift, 1) with concrete "infinitesimals": lift' = B^5 |p|^2 + B^rank, rank
// 4 for the largest index down to 0. For coordinates in [-3, 3] every
// coefficient is far below B, so the sign is that of the symbolic limit.
// Evaluated as a plain permutation sum (independent of the cofactor
// formula used by the implementation).
int insphere_sos_ref(const int* const* p, const int64_t* idx) {
  const i128 B = i128(1) << 16;
  i128 m[5][5];
  for (int r = 0; r < 5; ++r) {
    int rank = 0;
    for (int s = 0; s < 5; ++s) rank += idx[s] < idx[r];
    i128 raise = 1;
    for (int k = 0; k < rank; ++k) raise *= B;
    i128 lift = i128(p[r][0]) * p[r][0] + i128(p[r][1]) * p[r][1] + i128(p[r][2]) * p[r][2];
    m[r][0] = p[r][0], m[r][1] = p[r][1], m[r][2] = p[r][2];
    m[r][3] = B * B * B * B * B * lift + raise;
    m[r][4] = 1;
  }
  int perm[5] = {0, 1, 2, 3, 4};
  i128 det = 0;
  do {
    int inversions = 0;
    for (int i = 0; i < 5; ++i)
      for (int j = i + 1; j < 5; ++j) inversions += perm[i] > perm[j];
    i128 term = inversions % 2 ? -1 : 1;
    for (int r = 0; r < 5; ++r) term *= m[r][perm[r]];
    det += term;
  } while (std::next_permutation(perm, perm + 5));
  return sign(det);
}

// Degenerate sets: the 3x3x3 grid (cospherical and coplanar everywhere) and
// the integer points of the sphere of radius 3.
std::vector<std::array<int, 3>> degenerate_set(bool sphere) {
  std::vector<std::array<int, 3>> pts;
  for (int x = -3; x <= 3; ++x)
    for (int y = -3; y <= 3; ++y)
      for (int z = -3; z <= 3; ++z) {
        bool keep = sphere ? x * x + y * y + z * z == 9
                           : (std::abs(x) <= 1 && std::abs(y) <= 1 && std::abs(z) <= 1);
        if (keep) pts.push_back({x, y, z});
      }
  return pts;
}

TEST(Predicates, InsphereSosMatchesPerturbedDeterminantOnDegenerateSets) {
  std::mt19937 rng(11);
  for (bool sphere : {false, true}) {
    auto pts = degenerate_set(sphere);
    int ties = 0, coplanar = 0;
    for (int it = 0; it < 20000; ++it) {
      int pick[5];
      for (int i = 0; i < 5; ++i) {
        bool fresh;
        do {
          pick[i] = int(rng() % pts.size());
          fresh = true;
          for (int j = 0; j < i; ++j) fresh = fresh && pick[j] != pick[i];
        } while (!fresh);
      }
      double d[5][3];
      const int* q[5];
      int64_t idx[5];
      for (int i = 0; i < 5; ++i) {
        for (int k = 0; k < 3; ++k) d[i][k] = pts[pick[i]][k] + 0.5;  // off the origin
        q[i] = pts[pick[i]].data();
        idx[i] = pick[i];
      }
      int s = insphere_sos(d[0], d[1], d[2], d[3], d[4], idx[0], idx[1], idx[2], idx[3], idx[4]);
      ASSERT_EQ(s, insphere_sos_ref(q, idx)) << it;
      double plain = insphere(d[0], d[1], d[2], d[3], d[4]);
      if (plain != 0) {
        ASSERT_EQ(s, sign(plain));
      }
      ties += plain == 0;
      // Zero only when all five are coplanar.
      i128 qi[5][3];
      for (int i = 0; i < 5; ++i)
        for (int k = 0; k < 3; ++k) qi[i][k] = q[i][k];
      bool flat = true;
      for (int r = 0; r < 5 && flat; ++r) {
        const i128* o[4];
        for (int i = 0, n = 0; i < 5; ++i)
          if (i != r) o[n++] = qi[i];
        flat = orient3d_ref(o[0], o[1], o[2], o[3]) == 0;
      }
      coplanar += flat;
      ASSERT_EQ(s == 0, flat) << it;
    }
    EXPECT_GT(ties, 1000) << "the set should be degenerate";
    EXPECT_GT(coplanar, 0);
  }
}

TEST(Predicates, InsphereSosIsAntisymmetric) {
  // Swapping two points (with their indices) negates the perturbed
  // determinant, as it does the exact one.
  auto pts = degenerate_set(true);
  std::mt19937 rng(5);
  for (int it = 0; it < 5000; ++it) {
    std::vector<int> pick(pts.size());
    for (size_t i = 0; i < pick.size(); ++i) pick[i] = int(i);
    std::shuffle(pick.begin(), pick.end(), rng);
    double d[5][3];
    int64_t idx[5];
    for (int i = 0; i < 5; ++i) {
      for (int k = 0; k < 3; ++k) d[i][k] = pts[pick[i]][k] * 0.25 + 7;
      idx[i] = pick[i] * 3 + 100;
    }
    int s = insphere_sos(d[0], d[1], d[2], d[3], d[4], idx[0], idx[1], idx[2], idx[3], idx[4]);
    int i = int(rng() % 5), j = int((i + 1 + rng() % 4) % 5);
    std::swap(d[i], d[j]);
    std::swap(idx[i], idx[j]);
    int t = insphere_sos(d[0], d[1], d[2], d[3], d[4], idx[0], idx[1], idx[2], idx[3], idx[4]);
    ASSERT_EQ(s, -t) << it;
  }
}

}  // namespace
}  // namespace vm
