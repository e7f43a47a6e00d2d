// An independent exact evaluation of the predicates for tests: arbitrary-
// length expansion arithmetic (Shewchuk 1997) on std::vector, the
// determinants expanded about the last point (the coordinate differences
// kept exact as two-term expansions). core/geom/predicates.cpp evaluates
// the same signs another way (the coordinates' own minors on fixed arrays).
#pragma once

#include <vector>

#include "core/geom/error_free.h"

namespace vm::test {

/// An exact real number as a non-overlapping sum of doubles, increasing.
class Expansion {
 public:
  Expansion() = default;
  explicit Expansion(double x) {
    if (x != 0) terms_.push_back(x);
  }
  /// a - b exactly.
  static Expansion difference(double a, double b) {
    Expansion r;
    double x, y;
    exact::two_sum(a, -b, x, y);
    if (y != 0) r.terms_.push_back(y);
    if (x != 0) r.terms_.push_back(x);
    return r;
  }
  Expansion operator+(const Expansion& o) const {
    Expansion r = *this;
    for (double b : o.terms_) r.grow(b);
    return r;
  }
  Expansion operator-(const Expansion& o) const {
    Expansion neg = o;
    for (double& t : neg.terms_) t = -t;
    return *this + neg;
  }
  Expansion operator*(const Expansion& o) const {
    Expansion r;
    for (double b : o.terms_)
      for (double a : terms_) {
        double x, y;
        exact::two_product(a, b, x, y);
        r.grow(y);
        r.grow(x);
      }
    return r;
  }
  /// Sign of the exact value: the sign of its largest term.
  int sign() const { return terms_.empty() ? 0 : (terms_.back() > 0 ? 1 : -1); }

 private:
  // Adds one double (Grow-Expansion, zeros removed).
  void grow(double b) {
    if (b == 0) return;
    std::vector<double> next;
    next.reserve(terms_.size() + 1);
    double q = b;
    for (double a : terms_) {
      double x, y;
      exact::two_sum(q, a, x, y);
      if (y != 0) next.push_back(y);
      q = x;
    }
    if (q != 0) next.push_back(q);
    terms_.swap(next);
  }
  std::vector<double> terms_;
};

inline Expansion ediff(double a, double b) { return Expansion::difference(a, b); }

inline Expansion edet2(const Expansion& a, const Expansion& b, const Expansion& c,
                       const Expansion& d) {
  return a * d - b * c;
}

/// Exact signs of orient2d, incircle, orient3d and insphere (predicates.h).
inline int orient2d_sign(const double* a, const double* b, const double* c) {
  return edet2(ediff(a[0], c[0]), ediff(a[1], c[1]), ediff(b[0], c[0]), ediff(b[1], c[1])).sign();
}

inline int incircle_sign(const double* a, const double* b, const double* c, const double* d) {
  Expansion adx = ediff(a[0], d[0]), ady = ediff(a[1], d[1]);
  Expansion bdx = ediff(b[0], d[0]), bdy = ediff(b[1], d[1]);
  Expansion cdx = ediff(c[0], d[0]), cdy = ediff(c[1], d[1]);
  Expansion det = (adx * adx + ady * ady) * edet2(bdx, bdy, cdx, cdy) +
                  (bdx * bdx + bdy * bdy) * edet2(cdx, cdy, adx, ady) +
                  (cdx * cdx + cdy * cdy) * edet2(adx, ady, bdx, bdy);
  return det.sign();
}

// det[a; b; c] of expansion rows.
inline Expansion edet3(const Expansion* a, const Expansion* b, const Expansion* c) {
  return a[2] * edet2(b[0], b[1], c[0], c[1]) + b[2] * edet2(c[0], c[1], a[0], a[1]) +
         c[2] * edet2(a[0], a[1], b[0], b[1]);
}

inline int orient3d_sign(const double* a, const double* b, const double* c, const double* d) {
  Expansion ad[3], bd[3], cd[3];
  for (int k = 0; k < 3; ++k)
    ad[k] = ediff(a[k], d[k]), bd[k] = ediff(b[k], d[k]), cd[k] = ediff(c[k], d[k]);
  return edet3(ad, bd, cd).sign();
}

inline int insphere_sign(const double* a, const double* b, const double* c, const double* d,
                         const double* e) {
  Expansion ae[3], be[3], ce[3], de[3];
  for (int k = 0; k < 3; ++k) {
    ae[k] = ediff(a[k], e[k]), be[k] = ediff(b[k], e[k]);
    ce[k] = ediff(c[k], e[k]), de[k] = ediff(d[k], e[k]);
  }
  auto lift = [](const Expansion* p) { return p[0] * p[0] + p[1] * p[1] + p[2] * p[2]; };
  Expansion det = lift(de) * edet3(ae, be, ce) - lift(ce) * edet3(de, ae, be) +
                  lift(be) * edet3(ce, de, ae) - lift(ae) * edet3(be, ce, de);
  return det.sign();
}

}  // namespace vm::test
