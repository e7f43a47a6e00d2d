// Union-find whose unions may run on several threads at once (parallel.h):
// roots are linked under smaller roots with a compare-and-swap, so every
// set ends up rooted at its smallest element whatever the order of the
// unions, and the result does not depend on the thread count.
#pragma once

#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace vm {

class ConcurrentUnionFind {
 public:
  /// n singletons 0..n-1.
  explicit ConcurrentUnionFind(size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }

  /// The root of x (path halving; safe during concurrent unions).
  int32_t find(int32_t x) {
    while (true) {
      int32_t p = load(x);
      if (p == x) return x;
      const int32_t g = load(p);
      if (g != p) swap_parent(x, p, g);
      x = g;
    }
  }

  /// Joins the sets of a and b.
  void unite(int32_t a, int32_t b) {
    while (true) {
      a = find(a);
      b = find(b);
      if (a == b) return;
      if (a < b) std::swap(a, b);  // link the larger root under the smaller
      if (swap_parent(a, a, b)) return;
    }
  }

  /// After the unions: every element's root (its set's smallest element).
  /// Parents never exceed their children, so one pass in order suffices.
  std::vector<int32_t> roots() && {
    for (size_t i = 0; i < parent_.size(); ++i) parent_[i] = parent_[size_t(parent_[i])];
    return std::move(parent_);
  }

 private:
  // The compiler's atomic builtins on the plain array (std::atomic_ref is
  // missing from the WebAssembly toolchain's library).
  int32_t load(int32_t i) const { return __atomic_load_n(&parent_[size_t(i)], __ATOMIC_RELAXED); }
  /// parent[i]: from `expected` to `desired` if it still is `expected`.
  bool swap_parent(int32_t i, int32_t expected, int32_t desired) {
    return __atomic_compare_exchange_n(&parent_[size_t(i)], &expected, desired, false,
                                       __ATOMIC_ACQ_REL, __ATOMIC_RELAXED);
  }

  std::vector<int32_t> parent_;
};

}  // namespace vm
