// BRIO rounds (Amenta, Choi, Rote 2003) ordered along a Hilbert curve
// (Skilling 2004). Phases: (1) a deterministic Fisher-Yates shuffle, (2)
// cut into rounds of geometrically growing size, (3) per round, quantize to
// a 1024^3 grid over the bounding box (cubic cells, so elongated sets keep
// their aspect), compute Hilbert indices and radix-sort them.
#include "core/volume/spatial_sort.h"

#include <algorithm>
#include <cmath>

namespace vm {
namespace {

constexpr int kBits = 10;  // per axis: 2^30 cells, a 30-bit key

// splitmix64: a small, portable generator (std::shuffle's algorithm is not
// specified, so native and WebAssembly builds could differ).
uint64_t splitmix64(uint64_t& s) {
  uint64_t z = (s += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

struct Box {
  double lo[3] = {0, 0, 0};
  double scale = 0;  // cells per unit length
};

Box box_of(const std::vector<double>& points, const int32_t* ids, int64_t count) {
  Box b;
  if (count == 0) return b;
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) lo[k] = hi[k] = points[3 * size_t(ids[0]) + k];
  for (int64_t i = 1; i < count; ++i)
    for (int k = 0; k < 3; ++k) {
      double x = points[3 * size_t(ids[i]) + k];
      lo[k] = std::min(lo[k], x);
      hi[k] = std::max(hi[k], x);
    }
  double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  for (int k = 0; k < 3; ++k) b.lo[k] = lo[k];
  b.scale = extent > 0 ? double(1 << kBits) * (1 - 1e-12) / extent : 0;
  return b;
}

// Sorts ids[0, count) by Hilbert index on the grid of `box`: LSD radix sort
// of (key << 32 | position) in three 10-bit passes.
void sort_in_box(const std::vector<double>& points, const Box& box, int32_t* ids, int64_t count,
                 std::vector<uint64_t>& a, std::vector<uint64_t>& tmp) {
  if (count < 2) return;
  a.resize(size_t(count));
  tmp.resize(size_t(count));
  const uint32_t cmax = (1u << kBits) - 1;
  for (int64_t i = 0; i < count; ++i) {
    const double* p = &points[3 * size_t(ids[i])];
    uint32_t c[3];
    for (int k = 0; k < 3; ++k) {
      double x = (p[k] - box.lo[k]) * box.scale;
      c[k] = x <= 0 ? 0u : std::min(cmax, uint32_t(x));
    }
    a[size_t(i)] = (hilbert_index_3d(c[0], c[1], c[2], kBits) << 32) | uint64_t(uint32_t(ids[i]));
  }
  constexpr int kRadix = 10, kBuckets = 1 << kRadix;
  std::vector<int64_t> hist(kBuckets);
  for (int pass = 0; pass < 3; ++pass) {
    int shift = 32 + pass * kRadix;
    std::fill(hist.begin(), hist.end(), 0);
    for (uint64_t x : a) ++hist[(x >> shift) & (kBuckets - 1)];
    int64_t sum = 0;
    for (auto& h : hist) {
      int64_t c = h;
      h = sum;
      sum += c;
    }
    for (uint64_t x : a) tmp[size_t(hist[(x >> shift) & (kBuckets - 1)]++)] = x;
    a.swap(tmp);
  }
  for (int64_t i = 0; i < count; ++i) ids[i] = int32_t(uint32_t(a[size_t(i)]));
}

}  // namespace

uint64_t hilbert_index_3d(uint32_t x, uint32_t y, uint32_t z, int bits) {
  // Skilling's AxesToTranspose, then the transposed bits interleaved.
  uint32_t X[3] = {x, y, z};
  const uint32_t m = 1u << (bits - 1);
  for (uint32_t q = m; q > 1; q >>= 1) {  // inverse undo
    uint32_t p = q - 1;
    for (int i = 0; i < 3; ++i) {
      if (X[i] & q) {
        X[0] ^= p;  // invert
      } else {
        uint32_t t = (X[0] ^ X[i]) & p;  // exchange
        X[0] ^= t;
        X[i] ^= t;
      }
    }
  }
  for (int i = 1; i < 3; ++i) X[i] ^= X[i - 1];  // Gray encode
  uint32_t t = 0;
  for (uint32_t q = m; q > 1; q >>= 1)
    if (X[2] & q) t ^= q - 1;
  for (int i = 0; i < 3; ++i) X[i] ^= t;
  uint64_t h = 0;
  for (int b = bits - 1; b >= 0; --b)
    for (int i = 0; i < 3; ++i) h = (h << 1) | ((X[i] >> b) & 1u);
  return h;
}

void hilbert_sort(const std::vector<double>& points, int32_t* ids, int64_t count) {
  std::vector<uint64_t> a, tmp;
  sort_in_box(points, box_of(points, ids, count), ids, count, a, tmp);
}

std::vector<int32_t> brio_hilbert_order(const std::vector<double>& points,
                                        const SpatialSortOptions& options) {
  const int64_t n = int64_t(points.size() / 3);
  std::vector<int32_t> order(static_cast<size_t>(n));
  for (int64_t i = 0; i < n; ++i) order[size_t(i)] = int32_t(i);
  if (n < 2) return order;
  // Phase 1: shuffle.
  uint64_t s = options.seed;
  for (int64_t i = n - 1; i > 0; --i) {
    int64_t j = int64_t(splitmix64(s) % uint64_t(i + 1));
    std::swap(order[size_t(i)], order[size_t(j)]);
  }
  // Phase 2 + 3: rounds from the last (largest) down, each Hilbert-sorted in
  // the box of the whole set.
  const Box box = box_of(points, order.data(), n);
  const double ratio = std::clamp(options.round_ratio, 0.0, 0.9);
  const int64_t min_round = std::max<int64_t>(1, options.min_round);
  std::vector<uint64_t> a, tmp;
  int64_t end = n;
  while (end > 0) {
    int64_t start = int64_t(std::floor(double(end) * ratio));
    if (start < min_round) start = 0;
    sort_in_box(points, box, order.data() + start, end - start, a, tmp);
    end = start;
  }
  return order;
}

}  // namespace vm
