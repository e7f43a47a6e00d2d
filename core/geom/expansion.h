// Exact floating-point expansion arithmetic (Shewchuk 1997): a number is a
// sum of non-overlapping doubles, stored in increasing magnitude. Sums and
// products of expansions are exact (barring overflow). Products use Dekker's
// splitting rather than FMA so results are identical in WebAssembly.
#pragma once

#include <vector>

namespace vm::exact {

/// An exact real number as a non-overlapping sum of doubles.
class Expansion {
 public:
  Expansion() = default;
  explicit Expansion(double x) {
    if (x != 0) terms_.push_back(x);
  }
  /// a - b exactly.
  static Expansion difference(double a, double b);

  Expansion operator+(const Expansion& o) const;
  Expansion operator-(const Expansion& o) const;
  Expansion operator*(const Expansion& o) const;
  /// Sign of the exact value: the sign of its largest term.
  int sign() const { return terms_.empty() ? 0 : (terms_.back() > 0 ? 1 : -1); }
  /// Approximate value (sum of the terms).
  double estimate() const;

 private:
  Expansion scaled(double b) const;
  std::vector<double> terms_;  // increasing magnitude, no zeros
};

}  // namespace vm::exact
