#include "core/geom/hilbert_sort.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

#include "tests/support/volume_inputs.h"

namespace vm {
namespace {

TEST(HilbertSort, HilbertIndexIsABijectionWithFaceAdjacentSteps) {
  for (int bits : {1, 2, 3, 4, 5, 6}) {
    const uint32_t side = 1u << bits;
    std::vector<int> cell_of(size_t(side) * side * side, -1);
    for (uint32_t x = 0; x < side; ++x)
      for (uint32_t y = 0; y < side; ++y)
        for (uint32_t z = 0; z < side; ++z) {
          uint64_t h = hilbert_index_3d(x, y, z, bits);
          ASSERT_LT(h, cell_of.size());
          ASSERT_EQ(cell_of[h], -1) << "index " << h << " used twice";
          cell_of[h] = int((x * side + y) * side + z);
        }
    for (size_t h = 1; h < cell_of.size(); ++h) {
      int a = cell_of[h - 1], b = cell_of[h];
      int dx = std::abs(a / int(side * side) - b / int(side * side));
      int dy = std::abs((a / int(side)) % int(side) - (b / int(side)) % int(side));
      int dz = std::abs(a % int(side) - b % int(side));
      ASSERT_EQ(dx + dy + dz, 1) << "bits " << bits << " step " << h;
    }
  }
}

TEST(HilbertSort, HilbertIndexIsInjectiveOnFineGrids) {
  // Up to 21 bits per axis (63-bit indices): distinct cells get distinct
  // indices below 2^(3 bits).
  std::mt19937_64 rng(4);
  for (int bits : {7, 10, 16, 21}) {
    const uint32_t mask = (1u << bits) - 1;
    std::vector<uint64_t> cells, idx;
    for (int i = 0; i < 20000; ++i) {
      const uint32_t x = uint32_t(rng()) & mask, y = uint32_t(rng()) & mask,
                     z = uint32_t(rng()) & mask;
      cells.push_back((uint64_t(x) << 42) | (uint64_t(y) << 21) | z);
      idx.push_back(hilbert_index_3d(x, y, z, bits));
      ASSERT_LT(idx.back(), uint64_t(1) << (3 * bits));
    }
    std::sort(cells.begin(), cells.end());
    std::sort(idx.begin(), idx.end());
    const size_t distinct = size_t(std::unique(cells.begin(), cells.end()) - cells.begin());
    EXPECT_EQ(size_t(std::unique(idx.begin(), idx.end()) - idx.begin()), distinct) << bits;
  }
}

double mean_step(const std::vector<double>& p, const std::vector<int32_t>& order, size_t from,
                 size_t to) {
  double s = 0;
  for (size_t i = from + 1; i < to; ++i) {
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += std::pow(p[3 * order[i]] - p[3 * order[i - 1]], 2);
    s += std::sqrt(d2);
  }
  return s / double(to - from - 1);
}

TEST(HilbertSort, BrioOrderIsAPermutation) {
  for (int n : {0, 1, 2, 63, 64, 65, 1000, 20000}) {
    auto p = testing::random_cube_points(n, 7);
    auto order = brio_hilbert_order(p);
    ASSERT_EQ(order.size(), size_t(n));
    std::vector<int32_t> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (int i = 0; i < n; ++i) ASSERT_EQ(sorted[i], i);
    EXPECT_EQ(order, brio_hilbert_order(p)) << "deterministic";
  }
}

TEST(HilbertSort, ConsecutivePointsOfTheLastRoundAreClose) {
  const int n = 50000;
  auto p = testing::random_cube_points(n, 3);
  auto order = brio_hilbert_order(p);
  // The last round holds 7/8 of the points; in a random order the mean
  // step in the cube [-1,1]^3 is about 1.3; along the curve it is a few
  // times the mean spacing (8 / n)^(1/3) = 0.054.
  size_t from = size_t(n * 0.125) + 1;
  double step = mean_step(p, order, from, n);
  EXPECT_LT(step, 3 * std::cbrt(8.0 / (n - from)));
  std::vector<int32_t> identity(n);
  for (int i = 0; i < n; ++i) identity[i] = i;
  EXPECT_GT(mean_step(p, identity, 0, n), 1.0);
}

TEST(HilbertSort, HilbertSortHandlesDegenerateBoxes) {
  // All points equal, and points on a line: still a permutation.
  std::vector<double> p(3 * 100, 2.5);
  std::vector<int32_t> ids(100);
  for (int i = 0; i < 100; ++i) ids[i] = i;
  hilbert_sort(p, ids.data(), 100);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(ids[i], i) << "stable on ties";
  for (int i = 0; i < 100; ++i) p[3 * i] = double((i * 37) % 100);
  hilbert_sort(p, ids.data(), 100);
  std::vector<int32_t> sorted = ids;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < 100; ++i) EXPECT_EQ(sorted[i], i);
}

}  // namespace
}  // namespace vm
