// Union-find whose unions may run on several threads at once (parallel.h):
// roots are linked under smaller roots with a compare-and-swap, so every
// set ends up rooted at its smallest element whatever the order of the
// unions, and the result does not depend on the thread count.
#pragma once

#include <atomic>
#include <cstdint>
#include <numeric>
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
      int32_t p = ref(x).load(std::memory_order_relaxed);
      if (p == x) return x;
      const int32_t g = ref(p).load(std::memory_order_relaxed);
      if (g != p) ref(x).compare_exchange_weak(p, g, std::memory_order_relaxed);
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
      int32_t expected = a;
      if (ref(a).compare_exchange_strong(expected, b, std::memory_order_acq_rel)) return;
    }
  }

  /// After the unions: every element's root (its set's smallest element).
  /// Parents never exceed their children, so one pass in order suffices.
  std::vector<int32_t> roots() && {
    for (size_t i = 0; i < parent_.size(); ++i) parent_[i] = parent_[size_t(parent_[i])];
    return std::move(parent_);
  }

 private:
  std::atomic_ref<int32_t> ref(int32_t i) { return std::atomic_ref<int32_t>(parent_[size_t(i)]); }

  std::vector<int32_t> parent_;
};

}  // namespace vm
