// Expansion arithmetic after Shewchuk 1997 (expansion sum with zero
// elimination, scale-expansion) on the error-free transformations of
// error_free.h.
#include "core/geom/expansion.h"

#include <cmath>

#include "core/geom/error_free.h"

namespace vm::exact {
namespace {

// Sum of two expansions (each increasing, non-overlapping), zeros removed.
std::vector<double> sum(const std::vector<double>& e, const std::vector<double>& f) {
  std::vector<double> h;
  h.reserve(e.size() + f.size());
  // Grow one term at a time (Linear-Expansion-Sum would be faster; this is
  // the rare exact path).
  h = e;
  for (double b : f) {
    std::vector<double> next;
    next.reserve(h.size() + 1);
    double q = b;
    for (double a : h) {
      double x, y;
      two_sum(q, a, x, y);
      if (y != 0) next.push_back(y);
      q = x;
    }
    if (q != 0 || next.empty()) next.push_back(q);
    h.swap(next);
  }
  if (h.size() == 1 && h[0] == 0) h.clear();
  return h;
}

}  // namespace

Expansion Expansion::difference(double a, double b) {
  Expansion r;
  double x, y;
  two_sum(a, -b, x, y);
  if (y != 0) r.terms_.push_back(y);
  if (x != 0) r.terms_.push_back(x);
  return r;
}

Expansion Expansion::operator+(const Expansion& o) const {
  Expansion r;
  r.terms_ = sum(terms_, o.terms_);
  return r;
}

Expansion Expansion::operator-(const Expansion& o) const {
  Expansion neg = o;
  for (double& t : neg.terms_) t = -t;
  return *this + neg;
}

Expansion Expansion::scaled(double b) const {
  Expansion r;
  for (double a : terms_) {
    double x, y;
    two_product(a, b, x, y);
    Expansion p;
    if (y != 0) p.terms_.push_back(y);
    if (x != 0) p.terms_.push_back(x);
    r = r + p;
  }
  return r;
}

Expansion Expansion::operator*(const Expansion& o) const {
  Expansion r;
  for (double b : o.terms_) r = r + scaled(b);
  return r;
}

double Expansion::estimate() const {
  double s = 0;
  for (double t : terms_) s += t;
  return s;
}

}  // namespace vm::exact
