// Error-free transformations after Shewchuk 1997 ("Adaptive Precision
// Floating-Point Arithmetic and Fast Robust Geometric Predicates"): a sum or
// product of two doubles as a rounded value plus its exact rounding error.
// Products use Dekker's split rather than FMA so results are identical in
// WebAssembly. The building blocks of the exact predicates.
#pragma once

namespace vm::exact {

/// x + y = a + b exactly, |y| <= ulp(x)/2 (Two-Sum).
inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  double bv = x - a;
  double av = x - bv;
  y = (a - av) + (b - bv);
}

/// Dekker's split: a = hi + lo, each with at most 26 significant bits.
inline void split(double a, double& hi, double& lo) {
  constexpr double kSplitter = 134217729.0;  // 2^27 + 1
  double c = kSplitter * a;
  double big = c - a;
  hi = c - big;
  lo = a - hi;
}

/// x + y = a * b exactly (Two-Product).
inline void two_product(double a, double b, double& x, double& y) {
  x = a * b;
  double ahi, alo, bhi, blo;
  split(a, ahi, alo);
  split(b, bhi, blo);
  double err1 = x - ahi * bhi;
  double err2 = err1 - alo * bhi;
  double err3 = err2 - ahi * blo;
  y = alo * blo - err3;
}

}  // namespace vm::exact
