// BRIO rounds (Amenta, Choi, Rote 2003) ordered along a Hilbert curve
// (Skilling 2004). Phases: (1) every point's Hilbert index on a 1024^3
// grid over the bounding box (cubic cells, so elongated sets keep their
// aspect), (2) a deterministic Fisher-Yates shuffle, (3) cut into rounds of
// geometrically growing size, each radix-sorted by index.
#include "core/geom/hilbert_sort.h"

#include <algorithm>
#include <cmath>

#include "core/util/parallel.h"

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

// The bits of x (< 2^21) spread to every third position (bit k to 3 k).
uint64_t spread3(uint32_t x) {
  uint64_t v = x & 0x1fffffu;
  v = (v | v << 32) & 0x1f00000000ffffull;
  v = (v | v << 16) & 0x1f0000ff0000ffull;
  v = (v | v << 8) & 0x100f00f00f00f00full;
  v = (v | v << 4) & 0x10c30c30c30c30c3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

// The Hilbert index of point p (3 doubles) on the grid of `box`.
uint32_t cell_key(const double* p, const Box& box) {
  const uint32_t cmax = (1u << kBits) - 1;
  uint32_t c[3];
  for (int k = 0; k < 3; ++k) {
    double x = (p[k] - box.lo[k]) * box.scale;
    c[k] = x <= 0 ? 0u : std::min(cmax, uint32_t(x));
  }
  return uint32_t(hilbert_index_3d(c[0], c[1], c[2], kBits));
}

// Sorts ids[0, count) by key(i), the 30-bit key of position i: LSD radix
// sort of (key << 32 | id) in three 10-bit passes, stable.
template <class Key>
void sort_by_key(Key key, int32_t* ids, int64_t count, std::vector<uint64_t>& a,
                 std::vector<uint64_t>& tmp) {
  if (count < 2) return;
  a.resize(size_t(count));
  tmp.resize(size_t(count));
  for (int64_t i = 0; i < count; ++i)
    a[size_t(i)] = (uint64_t(key(i)) << 32) | uint64_t(uint32_t(ids[i]));
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
  // Skilling's AxesToTranspose, then the transposed bits interleaved. The
  // branches on the data are written as masks (the sort computes one index
  // per point, and random points mispredict half of them).
  uint32_t X[3] = {x, y, z};
  const uint32_t m = 1u << (bits - 1);
  for (uint32_t q = m; q > 1; q >>= 1) {  // inverse undo
    const uint32_t p = q - 1;
    // Axis 0: invert its low bits when its bit q is set.
    X[0] ^= p & (0u - ((X[0] & q) != 0));
    for (int i = 1; i < 3; ++i) {
      // Bit q set: invert the low bits of axis 0; else exchange them.
      const uint32_t set = 0u - ((X[i] & q) != 0);
      const uint32_t t = (X[0] ^ X[i]) & p & ~set;
      X[0] ^= (p & set) | t;
      X[i] ^= t;
    }
  }
  for (int i = 1; i < 3; ++i) X[i] ^= X[i - 1];  // Gray encode
  uint32_t t = 0;
  for (uint32_t q = m; q > 1; q >>= 1) t ^= (q - 1) & (0u - ((X[2] & q) != 0));
  for (int i = 0; i < 3; ++i) X[i] ^= t;
  // Bit b of axis i goes to bit 3 b + 2 - i.
  return (spread3(X[0]) << 2) | (spread3(X[1]) << 1) | spread3(X[2]);
}

void hilbert_sort(const std::vector<double>& points, int32_t* ids, int64_t count) {
  std::vector<uint64_t> a, tmp;
  const Box box = box_of(points, ids, count);
  sort_by_key([&](int64_t i) { return cell_key(&points[3 * size_t(ids[i])], box); }, ids, count, a,
              tmp);
}

std::vector<int32_t> brio_hilbert_order(const std::vector<double>& points,
                                        const SpatialSortOptions& options) {
  const int64_t n = int64_t(points.size() / 3);
  std::vector<int32_t> order(static_cast<size_t>(n));
  for (int64_t i = 0; i < n; ++i) order[size_t(i)] = int32_t(i);
  if (n < 2) return order;
  // Phase 1: every point's Hilbert index in the box of the whole set, read
  // in input order (the rounds below then gather 4-byte keys, not points),
  // on the threads.
  const Box box = box_of(points, order.data(), n);
  std::vector<uint32_t> key(static_cast<size_t>(n));
  parallel_for(size_t(n), size_t(1) << 15, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) key[i] = cell_key(&points[3 * i], box);
  });
  // Phase 2: shuffle.
  uint64_t s = options.seed;
  for (int64_t i = n - 1; i > 0; --i) {
    int64_t j = int64_t(splitmix64(s) % uint64_t(i + 1));
    std::swap(order[size_t(i)], order[size_t(j)]);
  }
  // Phase 3: rounds from the last (largest) down, each sorted by key.
  const double ratio = std::clamp(options.round_ratio, 0.0, 0.9);
  const int64_t min_round = std::max<int64_t>(1, options.min_round);
  std::vector<uint64_t> a, tmp;
  int64_t end = n;
  while (end > 0) {
    int64_t start = int64_t(std::floor(double(end) * ratio));
    if (start < min_round) start = 0;
    int32_t* ids = order.data() + start;
    sort_by_key([&](int64_t i) { return key[size_t(ids[i])]; }, ids, end - start, a, tmp);
    end = start;
  }
  return order;
}

}  // namespace vm
