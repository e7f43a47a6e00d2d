// Elementary functions from IEEE-754 basic operations only (see the
// header): Cody-Waite argument reduction (the reduction constant split so
// that its products with the quadrant or exponent are exact), then Taylor
// series, truncated where the next term is below 1e-19 of the result, on
// the reduced interval.
#include "core/util/portable_math.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace vm::pm {
namespace {

constexpr double kPi = 3.141592653589793;
constexpr double kPio2 = 1.5707963267948966;
constexpr double kPio2Lo = 6.123233995736766e-17;  // pi/2 - kPio2
constexpr double kPio6 = 0.5235987755982989;
constexpr double kPio6Lo = -5.360408832255455e-17;  // pi/6 - kPio6
constexpr double kSqrt3 = 1.7320508075688772;
constexpr double kTanPio12 = 0.2679491924311227;  // 2 - sqrt(3)
// pi/2 = kPio2A + kPio2B + kPio2C: the first two have 33 significant bits,
// so k * kPio2A and k * kPio2B are exact for |k| < 2^20.
constexpr double kPio2A = 1.5707963267341256;
constexpr double kPio2B = 6.077100506303966e-11;
constexpr double kPio2C = 2.0222662487959506e-21;
constexpr double kTwoOverPi = 0.6366197723675814;
constexpr double kReduceLimit = 524288.0;  // 2^19
// ln 2 = kLn2Hi + kLn2Lo, kLn2Hi with 32 significant bits (k * kLn2Hi exact
// for every exponent k of a double).
constexpr double kLn2Hi = 0.6931471806019545;
constexpr double kLn2Lo = -4.2009150726810846e-11;
constexpr double kLn2 = 0.6931471805599453;
constexpr double kInvLn2 = 1.4426950408889634;
constexpr double kSqrtHalf = 0.7071067811865476;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// sin r for |r| <= pi/4 (+ rounding): r - r^3/3! + ... - r^19/19!.
double sin_kernel(double r) {
  const double z = r * r;
  const double p =
      -1.0 / 6 +
      z * (1.0 / 120 +
           z * (-1.0 / 5040 +
                z * (1.0 / 362880 +
                     z * (-1.0 / 39916800 +
                          z * (1.0 / 6227020800 + z * (-1.0 / 1307674368000 +
                                                       z * (1.0 / 355687428096000 +
                                                            z * (-1.0 / 121645100408832000))))))));
  return r + r * z * p;
}

/// cos r for |r| <= pi/4 (+ rounding): 1 - r^2/2! + ... + r^20/20!.
double cos_kernel(double r) {
  const double z = r * r;
  const double p =
      1.0 / 24 +
      z * (-1.0 / 720 +
           z * (1.0 / 40320 +
                z * (-1.0 / 3628800 +
                     z * (1.0 / 479001600 + z * (-1.0 / 87178291200 +
                                                 z * (1.0 / 20922789888000 +
                                                      z * (-1.0 / 6402373705728000 +
                                                           z * (1.0 / 2432902008176640000))))))));
  const double half = 0.5 * z;
  const double w = 1 - half;
  // (1 - w) - half is the rounding error of w, added back.
  return w + (((1 - w) - half) + z * z * p);
}

/// x = k pi/2 + r with |r| <= pi/4 (about); returns k mod 4.
int reduce(double x, double& r) {
  const double k = std::nearbyint(x * kTwoOverPi);
  r = ((x - k * kPio2A) - k * kPio2B) - k * kPio2C;
  return int(static_cast<long long>(k) & 3);
}

/// 1/n! for n = 0..18 (the factorials are exact in double).
constexpr std::array<double, 19> kInvFactorial = [] {
  std::array<double, 19> t{};
  double f = 1;
  for (int n = 0; n < 19; ++n) {
    if (n > 1) f *= n;
    t[size_t(n)] = 1 / f;
  }
  return t;
}();

/// 1/n for odd n up to 31 (index n / 2), the atanh and atan series.
constexpr std::array<double, 16> kInvOdd = [] {
  std::array<double, 16> t{};
  for (int i = 0; i < 16; ++i) t[size_t(i)] = 1.0 / (2 * i + 1);
  return t;
}();

/// e^r - 1 for |r| <= 0.5: r + r^2/2! + ... + r^18/18!.
double expm1_kernel(double r) {
  double p = kInvFactorial[18];
  for (size_t n = 17; n >= 2; --n) p = p * r + kInvFactorial[n];
  return r + r * r * p;
}

/// log m for m in [sqrt(1/2), sqrt(2)), as f - (f^2/2 - s (f^2/2 + R)) with
/// f = m - 1 (exact), s = f / (2 + f) and 2 atanh(s) = 2 s + s R, R =
/// 2 s^2/3 + 2 s^4/5 + ... to s^22 (|s| < 0.172): the exact f carries the
/// result, the series only a small correction. plus_lo is added to that
/// correction (the low part of e ln 2).
double log_kernel(double m, double plus_lo = 0) {
  const double f = m - 1;
  const double s = f / (2 + f);
  const double z = s * s;
  double r = kInvOdd[11];
  for (size_t i = 10; i >= 1; --i) r = r * z + kInvOdd[i];
  r *= 2 * z;
  const double hfsq = 0.5 * f * f;
  return f - (hfsq - (s * (hfsq + r) + plus_lo));
}

/// sin(r + q pi/2) for |r| <= pi/4.
double sin_quadrant(double r, int q) {
  switch (q & 3) {
    case 0:
      return sin_kernel(r);
    case 1:
      return cos_kernel(r);
    case 2:
      return -sin_kernel(r);
    default:
      return -cos_kernel(r);
  }
}

}  // namespace

double sin(double x) {
  if (!(std::fabs(x) < kReduceLimit)) return std::isfinite(x) ? std::sin(x) : kNaN;
  double r;
  const int q = reduce(x, r);
  return sin_quadrant(r, q);
}

double cos(double x) {
  if (!(std::fabs(x) < kReduceLimit)) return std::isfinite(x) ? std::cos(x) : kNaN;
  double r;
  const int q = reduce(x, r);
  return sin_quadrant(r, q + 1);  // cos x = sin(x + pi/2)
}

double tan(double x) {
  if (!(std::fabs(x) < kReduceLimit)) return std::isfinite(x) ? std::tan(x) : kNaN;
  double r;
  const int q = reduce(x, r);
  const double s = sin_kernel(r), c = cos_kernel(r);
  return (q & 1) ? -c / s : s / c;
}

double atan(double x) {
  if (std::isnan(x)) return x;
  double a = std::fabs(x);
  const bool invert = a > 1;
  if (invert) a = 1 / a;
  // atan a = pi/6 + atan((sqrt3 a - 1) / (sqrt3 + a)) brings a to <= 2 - sqrt3.
  const bool shift = a > kTanPio12;
  if (shift) a = (kSqrt3 * a - 1) / (kSqrt3 + a);
  const double z = a * a;
  double p = -kInvOdd[15];  // a - a^3/3 + ... - a^31/31
  for (size_t i = 14; i + 1 > 0; --i) p = p * z + ((i & 1) ? -kInvOdd[i] : kInvOdd[i]);
  double t = a * p;
  if (shift) t = kPio6 + (kPio6Lo + t);
  if (invert) t = kPio2 + (kPio2Lo - t);
  return x < 0 ? -t : t;
}

double atan2(double y, double x) {
  if (std::isnan(x) || std::isnan(y)) return x + y;
  if (y == 0) return (x > 0 || (x == 0 && !std::signbit(x))) ? y : std::copysign(kPi, y);
  if (x == 0) return std::copysign(kPio2, y);
  if (std::isinf(x)) {
    if (std::isinf(y)) return std::copysign(x > 0 ? kPi / 4 : 3 * kPi / 4, y);
    return x > 0 ? std::copysign(0.0, y) : std::copysign(kPi, y);
  }
  if (std::isinf(y)) return std::copysign(kPio2, y);
  const double ax = std::fabs(x), ay = std::fabs(y);
  double t = ay > ax ? kPio2 + (kPio2Lo - atan(ax / ay)) : atan(ay / ax);
  if (x < 0) t = kPi - t;
  return std::copysign(t, y);
}

double asin(double x) {
  if (!(std::fabs(x) <= 1)) return kNaN;
  return atan2(x, std::sqrt((1 - x) * (1 + x)));
}

double acos(double x) {
  if (!(std::fabs(x) <= 1)) return kNaN;
  return atan2(std::sqrt((1 - x) * (1 + x)), x);
}

double exp(double x) {
  if (std::isnan(x)) return x;
  if (x > 709.782712893384) return kInf;
  if (x < -745.2) return 0;
  const double k = std::nearbyint(x * kInvLn2);
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;  // |r| <= 0.347 (about)
  return std::ldexp(1 + expm1_kernel(r), int(k));
}

double expm1(double x) {
  if (std::fabs(x) <= 0.5) return expm1_kernel(x);
  if (x < -40) return -1;
  return exp(x) - 1;
}

double exp2(double x) {
  if (std::isnan(x)) return x;
  if (x > 1024) return kInf;
  if (x < -1080) return 0;
  const double n = std::nearbyint(x);
  const double f = x - n;  // exact
  return std::ldexp(f == 0 ? 1.0 : exp(f * kLn2), int(n));
}

namespace {
/// x = m 2^e with m in [sqrt(1/2), sqrt(2)), for finite x > 0.
double split_exponent(double x, int& e) {
  double m = std::frexp(x, &e);
  if (m < kSqrtHalf) {
    m *= 2;
    e -= 1;
  }
  return m;
}

/// The logarithms' results outside finite x > 0 (NaN, -infinity, +infinity);
/// false for finite x > 0.
bool log_edge(double x, double& out) {
  if (std::isnan(x) || x < 0) return out = kNaN, true;
  if (x == 0) return out = -kInf, true;
  if (std::isinf(x)) return out = x, true;
  return false;
}
}  // namespace

double log(double x) {
  if (double edge; log_edge(x, edge)) return edge;
  int e;
  const double m = split_exponent(x, e);
  return e * kLn2Hi + log_kernel(m, e * kLn2Lo);
}

double log2(double x) {
  if (double edge; log_edge(x, edge)) return edge;
  int e;
  const double m = split_exponent(x, e);
  return m == 1 ? double(e) : e + log_kernel(m) * kInvLn2;
}

double pow(double x, double y) {
  if (y == 0) return 1;
  if (x == 0) return y > 0 ? 0.0 : kInf;
  if (!(x > 0)) return kNaN;
  if (x == 1) return 1;
  return exp(y * log(x));
}

double cbrt(double x) {
  if (x == 0 || !std::isfinite(x)) return x;
  const double a = std::fabs(x);
  double y = exp(log(a) / 3);
  y -= (y - a / (y * y)) / 3;  // one Newton step
  return std::copysign(y, x);
}

double hypot(double x, double y) {
  x = std::fabs(x);
  y = std::fabs(y);
  if (std::isinf(x) || std::isinf(y)) return kInf;
  if (std::isnan(x) || std::isnan(y)) return x + y;
  if (x < y) {
    const double t = x;
    x = y;
    y = t;
  }
  if (y == 0) return x;
  if (x < 1e150 && y > 1e-150) return std::sqrt(x * x + y * y);
  const double r = y / x;
  return x * std::sqrt(1 + r * r);
}

double hypot(double x, double y, double z) {
  x = std::fabs(x);
  y = std::fabs(y);
  z = std::fabs(z);
  if (std::isinf(x) || std::isinf(y) || std::isinf(z)) return kInf;
  if (std::isnan(x) || std::isnan(y) || std::isnan(z)) return x + y + z;
  const double m = std::max(x, std::max(y, z));
  if (m == 0) return 0;
  if (m < 1e150 && m > 1e-150) return std::sqrt(x * x + y * y + z * z);
  x /= m;
  y /= m;
  z /= m;
  return m * std::sqrt(x * x + y * y + z * z);
}

}  // namespace vm::pm
