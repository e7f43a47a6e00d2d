// Least-significant-digit radix sorts of 64-bit keys and of doubles, for the
// sorts of millions of keys or coordinates where std::sort's comparisons
// dominate.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

namespace vm {

/// Sorts `keys` (n unsigned 64-bit integers) ascending by their bits from
/// `from_bit` up (0: the whole key); keys equal there keep their order.
/// Passes of 11 bits, skipping the digits all keys share; O(n) time, n
/// extra keys.
inline void radix_sort(std::vector<uint64_t>& keys, int from_bit = 0) {
  const size_t n = keys.size();
  if (n < 2) return;
  constexpr int kBits = 11;
  constexpr size_t kBuckets = size_t(1) << kBits;
  const int passes = (64 - from_bit + kBits - 1) / kBits;
  std::vector<uint64_t> other(n);
  std::vector<std::array<uint32_t, kBuckets>> count(static_cast<size_t>(passes));
  for (auto& c : count) c.fill(0);
  for (const uint64_t k : keys)
    for (int p = 0; p < passes; ++p)
      ++count[size_t(p)][(k >> (from_bit + kBits * p)) & (kBuckets - 1)];
  for (int p = 0; p < passes; ++p) {
    std::array<uint32_t, kBuckets>& c = count[size_t(p)];
    const int shift = from_bit + kBits * p;
    if (c[(keys[0] >> shift) & (kBuckets - 1)] == n) continue;  // one digit for all
    uint32_t sum = 0;
    for (uint32_t& x : c) {
      const uint32_t here = x;
      x = sum;
      sum += here;
    }
    for (size_t i = 0; i < n; ++i) other[c[(keys[i] >> shift) & (kBuckets - 1)]++] = keys[i];
    keys.swap(other);
  }
}

/// Sorts `values` (n doubles, no NaN) ascending: the same sequence as
/// std::sort, except that -0 comes before +0 (std::sort leaves equal values
/// in any order). Sorts an order-preserving image of the bits.
inline void radix_sort(std::vector<double>& values) {
  // The bit image of a double that orders as unsigned integers: negatives
  // reversed, positives above them.
  auto to_key = [](double x) {
    uint64_t u;
    std::memcpy(&u, &x, 8);
    return (u >> 63) ? ~u : u | (uint64_t(1) << 63);
  };
  auto from_key = [](uint64_t k) {
    const uint64_t u = (k >> 63) ? k & ~(uint64_t(1) << 63) : ~k;
    double x;
    std::memcpy(&x, &u, 8);
    return x;
  };
  std::vector<uint64_t> keys(values.size());
  for (size_t i = 0; i < values.size(); ++i) keys[i] = to_key(values[i]);
  radix_sort(keys);
  for (size_t i = 0; i < values.size(); ++i) values[i] = from_key(keys[i]);
}

}  // namespace vm
