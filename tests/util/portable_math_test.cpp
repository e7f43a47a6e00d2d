#include "core/util/portable_math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

namespace vm {
namespace {

/// Distance in units in the last place between two finite doubles of one
/// sign (or both zero).
int64_t ulps(double a, double b) {
  if (a == b) return 0;
  int64_t ia, ib;
  std::memcpy(&ia, &a, 8);
  std::memcpy(&ib, &b, 8);
  if ((ia < 0) != (ib < 0)) return std::numeric_limits<int64_t>::max();
  return ia > ib ? ia - ib : ib - ia;
}

/// The C library's result (correct to about 1 ulp) as the reference.
void expect_close(const char* name, double (*ours)(double), double (*libm)(double), double lo,
                  double hi, int64_t max_ulps) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(lo, hi);
  int64_t worst = 0;
  double at = 0;
  for (int i = 0; i < 200000; ++i) {
    const double x = u(rng);
    const double want = libm(x);
    if (std::fabs(want) < 1e-300) continue;
    const int64_t d = ulps(ours(x), want);
    if (d > worst) worst = d, at = x;
  }
  EXPECT_LE(worst, max_ulps) << name << " at x = " << at;
}

/// One function against the C library's on uniform samples of [lo, hi].
struct CloseCase {
  const char* name;
  double (*ours)(double);
  double (*libm)(double);
  double lo, hi;
  int64_t max_ulps;
};

TEST(PortableMath, WithinAFewUlpsOfTheCLibrary) {
  const CloseCase cases[] = {
      {"sin", pm::sin, [](double x) { return std::sin(x); }, -40, 40, 2},
      {"cos", pm::cos, [](double x) { return std::cos(x); }, -40, 40, 2},
      {"sin small", pm::sin, [](double x) { return std::sin(x); }, -1e-3, 1e-3, 1},
      {"tan", pm::tan, [](double x) { return std::tan(x); }, -1.5, 1.5, 3},
      {"atan", pm::atan, [](double x) { return std::atan(x); }, -30, 30, 2},
      {"asin", pm::asin, [](double x) { return std::asin(x); }, -1, 1, 3},
      {"acos", pm::acos, [](double x) { return std::acos(x); }, -1, 1, 3},
      {"exp", pm::exp, [](double x) { return std::exp(x); }, -700, 700, 2},
      {"expm1", pm::expm1, [](double x) { return std::expm1(x); }, -2, 2, 2},
      {"exp2", pm::exp2, [](double x) { return std::exp2(x); }, -60, 60, 2},
      {"log", pm::log, [](double x) { return std::log(x); }, 1e-9, 1e9, 2},
      {"log near 1", pm::log, [](double x) { return std::log(x); }, 0.9, 1.1, 2},
      {"log2", pm::log2, [](double x) { return std::log2(x); }, 1e-9, 1e9, 2},
      {"cbrt", pm::cbrt, [](double x) { return std::cbrt(x); }, -1e6, 1e6, 3},
      {"pow", [](double x) { return pm::pow(x, -1.0 / 7); },
       [](double x) { return std::pow(x, -1.0 / 7); }, 1, 1e6, 2},
  };
  for (const CloseCase& c : cases) expect_close(c.name, c.ours, c.libm, c.lo, c.hi, c.max_ulps);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-50, 50);
  int64_t worst_atan2 = 0, worst_hypot = 0;
  for (int i = 0; i < 200000; ++i) {
    const double y = u(rng), x = u(rng);
    worst_atan2 = std::max(worst_atan2, ulps(pm::atan2(y, x), std::atan2(y, x)));
    worst_hypot = std::max(worst_hypot, ulps(pm::hypot(y, x), std::hypot(y, x)));
  }
  EXPECT_LE(worst_atan2, 3);
  EXPECT_LE(worst_hypot, 1);
}

TEST(PortableMath, ExactWhereTheMathIsExact) {
  EXPECT_EQ(pm::sin(0.0), 0.0);
  EXPECT_EQ(pm::cos(0.0), 1.0);
  EXPECT_EQ(pm::exp(0.0), 1.0);
  EXPECT_EQ(pm::log(1.0), 0.0);
  EXPECT_EQ(pm::atan2(0.0, 1.0), 0.0);
  EXPECT_EQ(pm::acos(1.0), 0.0);
  EXPECT_EQ(pm::acos(-1.0), 3.141592653589793);
  EXPECT_EQ(pm::hypot(3.0, 4.0), 5.0);
  EXPECT_EQ(pm::cbrt(-27.0), -3.0);
  for (int k = -1000; k <= 1000; ++k) {
    ASSERT_EQ(pm::log2(std::ldexp(1.0, k)), double(k)) << k;
    ASSERT_EQ(pm::exp2(double(k)), std::ldexp(1.0, k)) << k;
  }
}

TEST(PortableMath, EdgesFollowTheCLibrary) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(std::isnan(pm::sin(inf)));
  EXPECT_TRUE(std::isnan(pm::log(-1.0)));
  EXPECT_TRUE(std::isnan(pm::acos(1.5)));
  EXPECT_EQ(pm::log(0.0), -inf);
  EXPECT_EQ(pm::exp(1000.0), inf);
  EXPECT_EQ(pm::exp(-1000.0), 0.0);
  EXPECT_EQ(pm::atan2(1.0, 0.0), std::atan2(1.0, 0.0));
  EXPECT_EQ(pm::atan2(0.0, -1.0), std::atan2(0.0, -1.0));
  EXPECT_EQ(pm::atan2(-0.0, -1.0), std::atan2(-0.0, -1.0));
  EXPECT_EQ(pm::atan2(-1.0, -inf), std::atan2(-1.0, -inf));
  EXPECT_LE(ulps(pm::hypot(1e300, 1e300), std::hypot(1e300, 1e300)), 1);
  EXPECT_LE(ulps(pm::hypot(1e-300, 1e-300), std::hypot(1e-300, 1e-300)), 1);
  EXPECT_LE(ulps(pm::hypot(3e-200, 4e-200, 12e-200), 13e-200), 1);
  EXPECT_EQ(pm::atan(inf), std::atan(inf));
  EXPECT_EQ(pm::sin(1e7), std::sin(1e7));  // beyond the portable range
}

}  // namespace
}  // namespace vm
