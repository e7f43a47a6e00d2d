#include "core/volume/edge_removal.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <vector>

namespace vm {
namespace {

// A quality per triangle of the ring polygon (ring indices, sorted),
// drawn at random; some triangles invalid (-HUGE_VAL).
struct Table {
  std::map<std::array<int, 3>, double> q;
  double operator()(int x, int y, int z, double) const {
    std::array<int, 3> k{x, y, z};
    std::sort(k.begin(), k.end());
    return q.at(k);
  }
};

Table random_table(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  Table t;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k)
        t.q[{i, j, k}] = u(rng) < 0.1 ? -HUGE_VAL : std::round(u(rng) * 20) / 20;
  return t;
}

// The best smallest quality over every triangulation of the sub-polygon
// i .. j, by enumeration.
double brute(const Table& t, int i, int j) {
  if (j - i < 2) return 1e300;
  double best = -HUGE_VAL;
  for (int k = i + 1; k < j; ++k)
    best = std::max(best, std::min({t(i, k, j, 0), brute(t, i, k), brute(t, k, j)}));
  return best;
}

// The smallest quality of `tris`, checked to triangulate the n-gon: n - 2
// triangles whose edges are the polygon's sides once and diagonals twice.
double check_triangulation(const Table& t, int n, const std::vector<RingTriangle>& tris) {
  EXPECT_EQ(tris.size(), size_t(n - 2));
  std::map<std::pair<int, int>, int> edges;
  double q = 1e300;
  for (const RingTriangle& r : tris) {
    q = std::min(q, t(r[0], r[1], r[2], 0));
    for (int e = 0; e < 3; ++e) {
      const int a = r[size_t(e)], b = r[size_t(e + 1) % 3];
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  }
  for (const auto& [e, count] : edges) {
    const bool side = e.second - e.first == 1 || (e.first == 0 && e.second == n - 1);
    EXPECT_EQ(count, side ? 1 : 2) << e.first << "-" << e.second;
  }
  return q;
}

TEST(EdgeRemoval, DynamicProgramFindsTheBestTriangulation) {
  std::mt19937 rng(7);
  for (int n = 3; n <= kMaxProgramRing; ++n)
    for (int trial = 0; trial < 50; ++trial) {
      const Table t = random_table(n, rng);
      const double want = brute(t, 0, n - 1);
      std::vector<RingTriangle> tris;
      const double got = best_ring_triangulation(n, RingCandidates::kAll, -1, t, &tris);
      if (!(want > -1)) {
        EXPECT_LE(got, -1);
        EXPECT_TRUE(tris.empty());
        continue;
      }
      EXPECT_EQ(got, want) << "n " << n << " trial " << trial;
      EXPECT_EQ(check_triangulation(t, n, tris), want);
      // Without triangles, the same value; with a floor above it, none.
      EXPECT_EQ(best_ring_triangulation(n, RingCandidates::kAll, -1, t, nullptr), want);
      EXPECT_LE(best_ring_triangulation(n, RingCandidates::kAll, want, t, &tris), want);
      EXPECT_TRUE(tris.empty());
    }
}

TEST(EdgeRemoval, FansTakeTheFirstBestFanInFanOrder) {
  std::mt19937 rng(11);
  for (int n = 3; n <= 12; ++n)
    for (int trial = 0; trial < 20; ++trial) {
      const Table t = random_table(n, rng);
      double want = -1;
      int want_s = -1;
      for (int s = 0; s < (n == 3 ? 1 : n); ++s) {
        double q = 1e300;
        for (int i = 1; i + 1 < n; ++i) q = std::min(q, t(s, (s + i) % n, (s + i + 1) % n, 0));
        if (q > want) want = q, want_s = s;
      }
      std::vector<RingTriangle> tris;
      const double got = best_ring_triangulation(n, RingCandidates::kFans, -1, t, &tris);
      if (want_s < 0) {
        EXPECT_LE(got, -1);
        EXPECT_TRUE(tris.empty());
        continue;
      }
      EXPECT_EQ(got, want);
      ASSERT_EQ(tris.size(), size_t(n - 2));
      for (int i = 1; i + 1 < n; ++i)
        EXPECT_EQ(tris[size_t(i - 1)],
                  (RingTriangle{want_s, (want_s + i) % n, (want_s + i + 1) % n}));
      EXPECT_EQ(check_triangulation(t, n, tris), want);
    }
}

TEST(EdgeRemoval, RingRemovalTetsFollowTheTriangles) {
  const int32_t ring[5] = {10, 11, 12, 13, 14};
  const std::vector<RingTriangle> tris = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}};
  std::array<int32_t, 4> out[6];
  ring_removal_tets(1, 2, ring, tris, out);
  for (size_t i = 0; i < tris.size(); ++i) {
    std::array<int32_t, 4> two[2];
    ring_triangle_tets(1, 2, ring[tris[i][0]], ring[tris[i][1]], ring[tris[i][2]], two);
    EXPECT_EQ(out[2 * i], two[0]);
    EXPECT_EQ(out[2 * i + 1], two[1]);
  }
}

}  // namespace
}  // namespace vm
