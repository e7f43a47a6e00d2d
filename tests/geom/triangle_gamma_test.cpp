#include "core/geom/triangle_gamma.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace vm {
namespace {

double angle(const double* p, const double* q, const double* r) {
  double u[3], v[3], dot = 0, nu = 0, nv = 0;
  for (int k = 0; k < 3; ++k) {
    u[k] = q[k] - p[k];
    v[k] = r[k] - p[k];
    dot += u[k] * v[k];
    nu += u[k] * u[k];
    nv += v[k] * v[k];
  }
  return std::acos(dot / std::sqrt(nu * nv));
}

TEST(TriangleGamma, EquilateralIsOneDegenerateIsZero) {
  double a[3] = {0, 0, 0}, b[3] = {2, 0, 0}, c[3] = {1, std::sqrt(3.0), 0};
  EXPECT_NEAR(triangle_gamma(a, b, c), 1.0, 1e-12);
  double d[3] = {4, 0, 0};
  EXPECT_EQ(triangle_gamma(a, b, d), 0.0);
  EXPECT_EQ(triangle_gamma(a, a, b), 0.0);
}

TEST(TriangleGamma, MatchesTheSineFormulaOfTheSeed) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 200; ++i) {
    double p[3], q[3], r[3];
    for (int k = 0; k < 3; ++k) p[k] = u(rng), q[k] = u(rng), r[k] = u(rng);
    double A = angle(p, q, r), B = angle(q, r, p), C = angle(r, p, q);
    double sine =
        4 * std::sin(A) * std::sin(B) * std::sin(C) / (std::sin(A) + std::sin(B) + std::sin(C));
    EXPECT_NEAR(triangle_gamma(p, q, r), sine, 1e-9);
  }
}

TEST(TriangleGamma, RightIsoscelesValue) {
  double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
  EXPECT_NEAR(triangle_gamma(a, b, c), 2 * (std::sqrt(2.0) - 1), 1e-12);
}

}  // namespace
}  // namespace vm
