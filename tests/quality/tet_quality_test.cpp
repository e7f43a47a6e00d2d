#include "core/quality/tet_quality.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/quality/triangle_quality.h"

namespace vm {
namespace {

// Regular tetrahedron inscribed in the cube [-1, 1]^3, positively oriented.
std::vector<double> regular() {
  std::vector<double> p = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1};
  if (tet_volume6(&p[0], &p[3], &p[6], &p[9]) < 0) std::swap_ranges(&p[0], &p[3], &p[3]);
  return p;
}

double gamma_of(const std::vector<double>& p) { return tet_gamma(&p[0], &p[3], &p[6], &p[9]); }

// Applies x -> s R x + t, R a rotation about the axis (1, 2, 3) by `angle`.
std::vector<double> transform(const std::vector<double>& p, double s, double angle,
                              const double t[3]) {
  double k[3] = {1, 2, 3};
  const double n = std::sqrt(14.0);
  for (double& x : k) x /= n;
  const double c = std::cos(angle), si = std::sin(angle);
  std::vector<double> out(p.size());
  for (size_t i = 0; i < p.size(); i += 3) {
    const double* v = &p[i];
    const double kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    const double kxv[3] = {k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2],
                           k[0] * v[1] - k[1] * v[0]};
    for (int d = 0; d < 3; ++d)
      out[i + d] = s * (v[d] * c + kxv[d] * si + k[d] * kv * (1 - c)) + t[d];
  }
  return out;
}

TEST(TetQuality, RegularTetrahedronIsOne) {
  EXPECT_NEAR(gamma_of(regular()), 1.0, 1e-14);
  const DihedralRange r =
      tet_dihedral_range(&regular()[0], &regular()[3], &regular()[6], &regular()[9]);
  const double expected = std::acos(1.0 / 3.0) * 180 / std::numbers::pi;  // 70.5288
  EXPECT_NEAR(r.min, expected, 1e-10);
  EXPECT_NEAR(r.max, expected, 1e-10);
}

TEST(TetQuality, InvariantUnderSimilarity) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<double> p(12);
    for (double& x : p) x = u(rng);
    const double g = gamma_of(p);
    const double t[3] = {u(rng) * 10, u(rng) * 10, u(rng) * 10};
    for (double s : {1e-4, 1.0, 37.0, 1e4}) {
      const std::vector<double> q = transform(p, s, 2.0 * trial / 50.0, t);
      EXPECT_NEAR(gamma_of(q), g, 1e-9) << "trial " << trial << " scale " << s;
      const DihedralRange a = tet_dihedral_range(&p[0], &p[3], &p[6], &p[9]);
      const DihedralRange b = tet_dihedral_range(&q[0], &q[3], &q[6], &q[9]);
      EXPECT_NEAR(a.min, b.min, 1e-6);
      EXPECT_NEAR(a.max, b.max, 1e-6);
    }
    EXPECT_LE(std::abs(g), 1.0);
  }
}

TEST(TetQuality, FlatIsZeroInvertedIsNegative) {
  // Four coplanar corners (a sliver: a square split along both diagonals).
  const std::vector<double> flat = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  EXPECT_EQ(gamma_of(flat), 0.0);
  const DihedralRange r = tet_dihedral_range(&flat[0], &flat[3], &flat[6], &flat[9]);
  EXPECT_NEAR(r.min, 0.0, 1e-12);
  EXPECT_NEAR(r.max, 180.0, 1e-12);
  // Coincident corners.
  const std::vector<double> collapsed = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  EXPECT_EQ(gamma_of(collapsed), 0.0);
  // A near-sliver is near 0.
  std::vector<double> sliver = {0, 0, 0, 1, 0, 0, 1, 1, 1e-6, 0, 1, 0};
  EXPECT_GT(std::abs(gamma_of(sliver)), 0.0);
  EXPECT_LT(std::abs(gamma_of(sliver)), 1e-5);
  // Swapping two corners inverts: -gamma.
  std::vector<double> inv = regular();
  std::swap_ranges(&inv[0], &inv[3], &inv[3]);
  EXPECT_NEAR(gamma_of(inv), -1.0, 1e-14);
}

TEST(TetQuality, RightCornerTetrahedronValue) {
  // Corner of the unit cube: V = 1/6, faces 3 * 1/2 + sqrt(3)/2, longest
  // edge sqrt(2).
  std::vector<double> p = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const double expected =
      6 * std::sqrt(6.0) * (1.0 / 6) / ((1.5 + std::sqrt(3.0) / 2) * std::sqrt(2.0));
  EXPECT_NEAR(gamma_of(p), expected, 1e-14);  // 0.7320...
  const DihedralRange r = tet_dihedral_range(&p[0], &p[3], &p[6], &p[9]);
  EXPECT_NEAR(r.max, 90.0, 1e-12);
  EXPECT_NEAR(r.min, std::acos(1 / std::sqrt(3.0)) * 180 / std::numbers::pi, 1e-12);
}

TEST(TetQuality, PerTetVectorAndStats) {
  VolumeMesh m;
  m.points = regular();
  m.points.insert(m.points.end(), {0, 0, 3});
  m.tets = {0, 1, 2, 3, 0, 1, 2, 4};
  if (tet_volume6(&m.points[0], &m.points[3], &m.points[6], &m.points[12]) < 0)
    std::swap(m.tets[4], m.tets[5]);
  const std::vector<float> q = tet_qualities(m);
  ASSERT_EQ(q.size(), 2u);
  EXPECT_NEAR(q[0], 1.0, 1e-6);
  EXPECT_GT(q[1], 0.0f);
  EXPECT_LT(q[1], 1.0f);
  const QualityStats s = quality_stats(q);
  EXPECT_EQ(s.count, 2u);
  EXPECT_NEAR(s.max, 1.0, 1e-6);
  EXPECT_NEAR(s.min, q[1], 1e-7);
  const DihedralRange r = dihedral_range(m.points, m.tets);
  EXPECT_LT(r.min, 70.0);
  EXPECT_GT(r.max, 71.0);
}

}  // namespace
}  // namespace vm
