// Open-addressing hash table of int32 indices into caller-owned data: the
// caller supplies the hash and the equality test on indices, so keys are
// never copied (used to weld points and to find equal triangles).
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vm {

class IndexHashTable {
 public:
  /// Room for `expected` indices at load factor <= 1/2.
  explicit IndexHashTable(size_t expected) {
    size_t cap = std::bit_ceil(expected * 2 + 16);
    slots_.assign(cap, -1);
    mask_ = cap - 1;
  }

  /// Returns the stored index equal to `candidate` (eq(stored) is true), or
  /// inserts `candidate` and returns it. `hash` must be the hash of the
  /// candidate's key; `eq(i)` tests whether stored index i has that key.
  template <class Eq>
  int32_t find_or_insert(uint64_t hash, int32_t candidate, Eq&& eq) {
    size_t i = mix(hash) & mask_;
    while (true) {
      int32_t s = slots_[i];
      if (s < 0) {
        slots_[i] = candidate;
        return candidate;
      }
      if (eq(s)) return s;
      i = (i + 1) & mask_;
    }
  }

  /// Visits every stored index with this hash whose key may match.
  template <class Fn>
  void for_each_with_hash(uint64_t hash, Fn&& fn) const {
    size_t i = mix(hash) & mask_;
    while (slots_[i] >= 0) {
      fn(slots_[i]);
      i = (i + 1) & mask_;
    }
  }

  /// Final avalanche of splitmix64, so that weak hashes spread over slots.
  static uint64_t mix(uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return x;
  }

 private:
  std::vector<int32_t> slots_;
  size_t mask_ = 0;
};

}  // namespace vm
