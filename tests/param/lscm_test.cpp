#include "core/param/lscm.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>

#include "tests/param/param_test_meshes.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

using cplx = std::complex<double>;
constexpr double kPi = std::numbers::pi;
using testing::as_complex;
using testing::disk;
using testing::similarity_residual;

TEST(Lscm, ReproducesAPlanarPatchUpToSimilarity) {
  // A jittered disk in a tilted plane: the identity is conformal, so LSCM
  // must return the planar coordinates up to rotation, scale, translation.
  const double c = std::cos(0.7), s = std::sin(0.7);
  std::vector<cplx> planar;
  SurfaceMesh m = disk(
      12, 6, 0.3,
      [&](double x, double y) {
        return std::array<double, 3>{3 + x, 1 + c * y, -2 + s * y};
      },
      &planar);
  auto r = lscm(m);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().flipped_triangles, 0u);
  EXPECT_LT(similarity_residual(planar, as_complex(r.value().uv)), 1e-9);
  EXPECT_NEAR(r.value().conformal_energy, 0, 1e-10);
  // Orientation kept: positive area, and the pins where promised.
  EXPECT_GT(signed_area(m, r.value().uv), 0);
  EXPECT_EQ(r.value().uv[2 * size_t(r.value().pinned[0])], 0.0);
}

TEST(Lscm, UnrollsADevelopableCylinderStripExactly) {
  // Half a polyhedral cylinder (flat quads): its exact unrolling has each
  // column one chord wide.
  const int n = 16, rows = 8;
  const double R = 2.0, chord = 2 * R * std::sin(kPi / n / 2);
  SurfaceMesh m;
  std::vector<cplx> unrolled;
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= n; ++i) {
      double a = kPi * i / n;
      m.points.insert(m.points.end(), {R * std::cos(a), R * std::sin(a), 0.5 * j});
      unrolled.push_back({chord * i, 0.5 * j});
    }
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < n; ++i) {
      int32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.triangles.insert(m.triangles.end(), {a, b, d, a, d, c});
    }
  auto r = lscm(m);
  ASSERT_TRUE(r.ok()) << r.message();
  // (u, v) is orientation-preserving w.r.t. the outward normal; the
  // unrolling (angle, z) seen from outside is mirrored, so compare with the
  // conjugate.
  std::vector<cplx> w = as_complex(r.value().uv);
  double direct = similarity_residual(unrolled, w);
  for (cplx& x : unrolled) x = std::conj(x);
  double mirrored = similarity_residual(unrolled, w);
  EXPECT_LT(std::min(direct, mirrored), 1e-9);
  EXPECT_EQ(r.value().flipped_triangles, 0u);
}

TEST(Lscm, EnergyIdentityHolds) {
  // E_LSCM = E_D(u) + E_D(v) - A(u, v) for any map, here the LSCM of a
  // spherical cap and a random perturbation of it.
  SurfaceMesh cap = disk(14, 6, 0.25, [](double x, double y) {
    double r = std::hypot(x, y), t = 0.9 * r;  // polar angle up to ~52 degrees
    double phi = std::atan2(y, x);
    return std::array<double, 3>{std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi),
                                 std::cos(t)};
  });
  auto r = lscm(cap);
  ASSERT_TRUE(r.ok()) << r.message();
  std::vector<double> uv = r.value().uv;
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0, 0.01);
  for (int round = 0; round < 2; ++round) {
    std::vector<double> u(uv.size() / 2), v(uv.size() / 2);
    for (size_t i = 0; i < u.size(); ++i) u[i] = uv[2 * i], v[i] = uv[2 * i + 1];
    double lhs = conformal_energy(cap, uv);
    double rhs = dirichlet_energy(cap, u) + dirichlet_energy(cap, v) - signed_area(cap, uv);
    EXPECT_NEAR(lhs, rhs, 1e-10 * (dirichlet_energy(cap, u) + dirichlet_energy(cap, v)));
    for (double& x : uv) x += noise(rng);
  }
  // The LSCM minimizes the energy: the perturbed map costs more.
  EXPECT_GT(conformal_energy(cap, uv), r.value().conformal_energy);
}

TEST(Lscm, SphericalCapMapsWithoutFlipsAndNearlyConformal) {
  SurfaceMesh cap = disk(20, 6, 0.2, [](double x, double y) {
    double r = std::hypot(x, y), t = 1.2 * r, phi = std::atan2(y, x);
    return std::array<double, 3>{std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi),
                                 std::cos(t)};
  });
  auto r = lscm(cap);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r.value().flipped_triangles, 0u);
  // Angle preservation: compare each triangle's angles in 3D and in uv.
  double worst = 0, mean = 0;
  const auto& uv = r.value().uv;
  for (size_t t = 0; t < cap.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      int32_t a = cap.triangles[3 * t + k], b = cap.triangles[3 * t + (k + 1) % 3],
              c = cap.triangles[3 * t + (k + 2) % 3];
      auto angle3 = [&](const double* p, const double* q, const double* s) {
        double u[3], w[3], d = 0, nu = 0, nw = 0;
        for (int i = 0; i < 3; ++i)
          u[i] = q[i] - p[i], w[i] = s[i] - p[i], d += u[i] * w[i], nu += u[i] * u[i],
          nw += w[i] * w[i];
        return std::acos(std::clamp(d / std::sqrt(nu * nw), -1.0, 1.0));
      };
      double a3 = angle3(&cap.points[3 * size_t(a)], &cap.points[3 * size_t(b)],
                         &cap.points[3 * size_t(c)]);
      cplx pa = {uv[2 * size_t(a)], uv[2 * size_t(a) + 1]};
      cplx pb = {uv[2 * size_t(b)], uv[2 * size_t(b) + 1]};
      cplx pc = {uv[2 * size_t(c)], uv[2 * size_t(c) + 1]};
      double a2 = std::abs(std::arg((pc - pa) / (pb - pa)));
      worst = std::max(worst, std::abs(a2 - a3));
      mean += std::abs(a2 - a3);
    }
  }
  mean /= 3.0 * double(cap.num_triangles());
  EXPECT_LT(mean, 0.02);  // radians
  EXPECT_LT(worst, 0.2);
}

TEST(Lscm, RefusesClosedSurfaces) {
  auto r = lscm(testing::torus(12, 8));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("no boundary"), std::string::npos);
}

}  // namespace
}  // namespace vm
