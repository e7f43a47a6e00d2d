#include "core/util/parallel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/util/concurrent_union_find.h"
#include "core/util/radix_sort.h"

namespace vm {
namespace {

/// Restores the default thread count when a test ends.
struct ThreadCount {
  explicit ThreadCount(int n) { set_thread_count(n); }
  ~ThreadCount() { set_thread_count(0); }
};

TEST(ParallelFor, EveryIndexOnceInChunksOfTheGrain) {
  for (int threads : {1, 2, 4}) {
    ThreadCount tc(threads);
    for (size_t n : {size_t(0), size_t(1), size_t(999), size_t(1000), size_t(100'003)}) {
      std::vector<int> hits(n, 0);
      std::atomic<size_t> chunks{0};
      parallel_for(n, 1000, [&](size_t begin, size_t end) {
        EXPECT_EQ(begin % 1000, 0u);
        EXPECT_EQ(end, std::min(n, begin + 1000));
        for (size_t i = begin; i < end; ++i) ++hits[i];
        ++chunks;
      });
      EXPECT_EQ(chunks.load(), (n + 999) / 1000);
      for (size_t i = 0; i < n; ++i) ASSERT_EQ(hits[i], 1) << "n " << n << " index " << i;
    }
  }
}

TEST(ParallelSum, SameBitsWithAnyThreadCount) {
  // Terms of very different sizes: a different order of addition would give
  // a different rounding.
  std::vector<double> x(300'001);
  for (size_t i = 0; i < x.size(); ++i) x[i] = (i % 7 == 0 ? 1e12 : 1e-3) * double(i % 13 + 1);
  auto sum = [&](int threads) {
    ThreadCount tc(threads);
    return parallel_sum<double>(x.size(), 4096, [&](size_t b, size_t e) {
      double s = 0;
      for (size_t i = b; i < e; ++i) s += x[i];
      return s;
    });
  };
  const double one = sum(1);
  EXPECT_EQ(one, sum(2));
  EXPECT_EQ(one, sum(3));
  // A single chunk is the plain loop.
  ThreadCount tc(2);
  double plain = 0;
  for (size_t i = 0; i < 5000; ++i) plain += x[i];
  EXPECT_EQ(plain, parallel_sum<double>(5000, 5000, [&](size_t b, size_t e) {
              double s = 0;
              for (size_t i = b; i < e; ++i) s += x[i];
              return s;
            }));
}

TEST(ParallelFor, NestedLoopsAndExceptionsReachTheCaller) {
  ThreadCount tc(2);
  std::vector<int> hits(64 * 64, 0);
  parallel_for(64, 1, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i)
      parallel_for(64, 8, [&](size_t b2, size_t e2) {
        for (size_t j = b2; j < e2; ++j) ++hits[i * 64 + j];
      });
  });
  EXPECT_EQ(std::accumulate(hits.begin(), hits.end(), 0), 64 * 64);
  EXPECT_THROW(parallel_for(100, 1,
                            [&](size_t b, size_t) {
                              if (b == 37) throw std::runtime_error("chunk 37");
                            }),
               std::runtime_error);
  // The pool still works after an exception.
  std::atomic<int> count{0};
  parallel_for(100, 1, [&](size_t, size_t) { ++count; });
  EXPECT_EQ(count.load(), 100);
}

TEST(ParallelFor, ThreadCountFollowsTheSetting) {
  set_thread_count(3);
  EXPECT_EQ(thread_count(), threads_supported() ? 3 : 1);
  set_thread_count(0);
  EXPECT_GE(thread_count(), 1);
}

TEST(ParallelFor, ThreadLimitCapsTheSettingAndTheLoops) {
  if (!threads_supported()) GTEST_SKIP() << "a build without threads";
  set_thread_limit(2);
  set_thread_count(5);
  EXPECT_EQ(thread_count(), 2);
  set_thread_count(0);  // all cores, but at most the limit
  EXPECT_LE(thread_count(), 2);
  set_thread_count(5);
  // A loop of many slow chunks never has more than 2 threads in it at once.
  std::atomic<int> inside{0}, most{0};
  parallel_for(64, 1, [&](size_t, size_t) {
    const int now = ++inside;
    for (int seen = most.load(); now > seen && !most.compare_exchange_weak(seen, now);) {
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    --inside;
  });
  EXPECT_LE(most.load(), 2);
  set_thread_limit(0);
  EXPECT_EQ(thread_count(), 5);
  set_thread_count(0);
}

TEST(ConcurrentUnionFind, SetsRootedAtTheirSmallestElementWithAnyThreadCount) {
  // Random pairs over 200,000 elements: the sets are those of a plain
  // sequential union-find, each rooted at its smallest element.
  const size_t n = 200'000;
  std::vector<std::pair<int32_t, int32_t>> pairs(150'000);
  uint64_t s = 99;
  for (auto& [a, b] : pairs) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    a = int32_t((s >> 20) % n);
    b = int32_t((s >> 40) % n);
  }
  std::vector<int32_t> expected(n);
  std::iota(expected.begin(), expected.end(), 0);
  auto find = [&](int32_t x) {
    while (expected[size_t(x)] != x) x = expected[size_t(x)];
    return x;
  };
  for (auto [a, b] : pairs) {
    const int32_t ra = find(a), rb = find(b);
    if (ra != rb) expected[size_t(std::max(ra, rb))] = std::min(ra, rb);
  }
  for (size_t i = 0; i < n; ++i) expected[i] = find(int32_t(i));
  for (int threads : {1, 2, 4}) {
    ThreadCount tc(threads);
    ConcurrentUnionFind uf(n);
    parallel_for(pairs.size(), 1000, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) uf.unite(pairs[i].first, pairs[i].second);
    });
    EXPECT_EQ(std::move(uf).roots(), expected) << threads << " threads";
  }
}

TEST(RadixSort, KeysAndDoublesSortAsStdSort) {
  std::vector<uint64_t> keys(200'000);
  uint64_t s = 12345;
  for (uint64_t& k : keys) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    k = s ^ (s >> 29);
  }
  keys[7] = keys[8];  // a repeated key
  std::vector<uint64_t> expected = keys;
  std::sort(expected.begin(), expected.end());
  radix_sort(keys);
  EXPECT_EQ(keys, expected);
  // By the bits from 40 up only: equal there, keys keep their order.
  std::vector<uint64_t> high = {(uint64_t(3) << 40) | 7, (uint64_t(1) << 40) | 9,
                                (uint64_t(3) << 40) | 2, (uint64_t(1) << 40) | 1};
  radix_sort(high, 40);
  EXPECT_EQ(high, (std::vector<uint64_t>{(uint64_t(1) << 40) | 9, (uint64_t(1) << 40) | 1,
                                         (uint64_t(3) << 40) | 7, (uint64_t(3) << 40) | 2}));
  std::vector<double> values = {3.5, -1e300, 0.0, 2.0, -0.5, 1e-300, -2.0, 7.0, 3.5};
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  radix_sort(values);
  EXPECT_EQ(values, sorted);
}

}  // namespace
}  // namespace vm
