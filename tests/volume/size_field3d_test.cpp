#include "core/volume/size_field3d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/util/portable_math.h"

namespace vm {
namespace {

double brute_force(const std::vector<double>& pts, const std::vector<double>& h, double H, double g,
                   const double* x) {
  double best = H > 0 ? H : 1e300;
  for (size_t i = 0; i < h.size(); ++i) {
    const double* p = &pts[3 * i];
    const double d = std::sqrt((x[0] - p[0]) * (x[0] - p[0]) + (x[1] - p[1]) * (x[1] - p[1]) +
                               (x[2] - p[2]) * (x[2] - p[2]));
    best = std::min(best, h[i] + g * d);
  }
  return best;
}

struct Sample {
  std::vector<double> pts, h;
};

Sample random_sample(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), s(0.01, 0.2);
  Sample out;
  for (int i = 0; i < n; ++i) {
    out.pts.insert(out.pts.end(), {u(rng), u(rng), 0.3 * u(rng)});
    out.h.push_back(s(rng));
  }
  return out;
}

/// The field of the sample with core size H (0: none) and gradation g.
auto field_of(const Sample& s, double H, double g) {
  VolumeSizeOptions o;
  o.core_size = H;
  o.gradation = g;
  return VolumeSizeField::build(s.pts, s.h, o);
}

TEST(VolumeSizeField, MatchesBruteForceExactly) {
  for (int n : {1, 7, 9, 100, 2000}) {
    const Sample s = random_sample(n, 11u + uint32_t(n));
    for (double H : {0.0, 0.05, 0.3})
      for (double g : {0.0, 0.1, 0.25, 1.0}) {
        auto f = field_of(s, H, g);
        ASSERT_TRUE(f.ok()) << f.message();
        std::mt19937 rng(5);
        std::uniform_real_distribution<double> u(-2, 2);
        for (int q = 0; q < 200; ++q) {
          const double x[3] = {u(rng), u(rng), u(rng)};
          const double want = brute_force(s.pts, s.h, H, g, x);
          // Same terms, same arithmetic: the minimum is found exactly.
          EXPECT_EQ(f.value()(x), want) << "n " << n << " H " << H << " g " << g;
          // Any valid upper bound gives the same value; a bound below h
          // is returned as is.
          EXPECT_EQ(f.value().eval(x, want * 1.5 + 1), want);
          EXPECT_EQ(f.value().eval(x, want), want);
          EXPECT_EQ(f.value().eval(x, 0.5 * want), 0.5 * want);
        }
      }
  }
}

TEST(VolumeSizeField, ToleranceBoundsTheError) {
  const Sample s = random_sample(3000, 21);
  auto f = field_of(s, 0, 0.1);
  ASSERT_TRUE(f.ok());
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  for (double tol : {0.01, 0.1, 0.3})
    for (int q = 0; q < 300; ++q) {
      const double x[3] = {u(rng), u(rng), u(rng)};
      const double exact = f.value()(x);
      const double r = f.value().eval(x, VolumeSizeField::kNoBound, tol);
      EXPECT_GE(r, exact);
      EXPECT_LE(r, exact / (1 - tol) * (1 + 1e-12));
    }
}

TEST(VolumeSizeField, AtBoundaryPointsAndLipschitz) {
  const Sample s = random_sample(500, 3);
  auto f = field_of(s, 0, 0.2);
  ASSERT_TRUE(f.ok());
  for (size_t i = 0; i < s.h.size(); ++i) EXPECT_LE(f.value()(&s.pts[3 * i]), s.h[i]);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (int q = 0; q < 500; ++q) {
    const double x[3] = {u(rng), u(rng), u(rng)}, y[3] = {x[0] + 0.01 * u(rng), x[1], x[2]};
    EXPECT_LE(std::fabs(f.value()(x) - f.value()(y)), 0.2 * std::fabs(x[0] - y[0]) + 1e-15);
  }
  EXPECT_DOUBLE_EQ(f.value().min_size(), *std::min_element(s.h.begin(), s.h.end()));
}

TEST(VolumeSizeField, UniformBoundaryGrowsLinearlyAndIsCapped) {
  // Points on the unit sphere, all of size 0.1: inside, h = 0.1 + g (1 -
  // |x|) up to the distance to the nearest sample, capped by H.
  std::vector<double> pts, h;
  for (int i = 0; i < 2000; ++i) {
    const double z = 1 - 2 * (i + 0.5) / 2000, r = std::sqrt(1 - z * z), a = 2.399963 * i;
    pts.insert(pts.end(), {r * std::cos(a), r * std::sin(a), z});
    h.push_back(0.1);
  }
  VolumeSizeOptions o;
  o.gradation = 0.3;
  auto f = VolumeSizeField::build(pts, h, o);
  ASSERT_TRUE(f.ok());
  const double c[3] = {0, 0, 0};
  EXPECT_DOUBLE_EQ(f.value()(c), 0.1 + 0.3 * 1.0);
  o.core_size = 0.25;
  auto capped = VolumeSizeField::build(pts, h, o);
  ASSERT_TRUE(capped.ok());
  EXPECT_DOUBLE_EQ(capped.value()(c), 0.25);
}

TEST(VolumeSizeField, Errors) {
  VolumeSizeOptions o;
  EXPECT_FALSE(VolumeSizeField::build({}, {}, o).ok());
  EXPECT_FALSE(VolumeSizeField::build({0, 0}, {1}, o).ok());
  EXPECT_FALSE(VolumeSizeField::build({0, 0, 0}, {1, 2}, o).ok());
  EXPECT_FALSE(VolumeSizeField::build({0, 0, 0}, {0}, o).ok());
  EXPECT_FALSE(VolumeSizeField::build({0, 0, 0}, {-1}, o).ok());
  EXPECT_FALSE(VolumeSizeField::build({0, NAN, 0}, {1}, o).ok());
  EXPECT_FALSE(VolumeSizeField::build({0, 0, 0}, {INFINITY}, o).ok());
  o.gradation = -0.1;
  EXPECT_FALSE(VolumeSizeField::build({0, 0, 0}, {1}, o).ok());
  o.gradation = 0.2;
  o.core_size = -1;
  EXPECT_FALSE(VolumeSizeField::build({0, 0, 0}, {1}, o).ok());
  o.core_size = NAN;
  EXPECT_FALSE(VolumeSizeField::build({0, 0, 0}, {1}, o).ok());
}

TEST(VolumeSizeField, RefinementSpheresAreGradedMinima) {
  const Sample s = random_sample(200, 5);
  VolumeSizeOptions o;
  o.core_size = 0.5;
  o.gradation = 0.3;
  o.spheres.push_back({{0.2, -0.1, 0.0}, 0.25, 0.004});
  auto f = VolumeSizeField::build(s.pts, s.h, o);
  ASSERT_TRUE(f.ok()) << f.message();
  EXPECT_EQ(f.value().min_size(), 0.004);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 500; ++i) {
    const double x[3] = {u(rng), u(rng), u(rng)};
    const double d = pm::hypot(x[0] - 0.2, x[1] + 0.1, x[2]);  // as the field computes it
    const double want =
        std::min(brute_force(s.pts, s.h, 0.5, 0.3, x), 0.004 + 0.3 * std::max(0.0, d - 0.25));
    EXPECT_DOUBLE_EQ(f.value()(x), want);
  }
}

}  // namespace
}  // namespace vm
