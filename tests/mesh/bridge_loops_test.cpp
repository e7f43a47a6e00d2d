#include "core/mesh/bridge_loops.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "core/geom/vec3.h"

namespace vm {
namespace {

/// A circle of n points of radius r at height z, counterclockwise from +z,
/// starting at angle a0; returns the ids.
std::vector<int32_t> circle(std::vector<double>& pts, int n, double r, double z, double a0) {
  std::vector<int32_t> ids;
  for (int i = 0; i < n; ++i) {
    const double a = a0 + 2 * std::numbers::pi * i / n;
    ids.push_back(int32_t(pts.size() / 3));
    pts.insert(pts.end(), {r * std::cos(a), r * std::sin(a), z});
  }
  return ids;
}

TEST(BridgeLoops, MakesAnAnnulusUsingEveryLoopEdgeOnceConsistently) {
  std::vector<double> pts;
  const std::vector<int32_t> a = circle(pts, 12, 1.0, 0, 0);
  const std::vector<int32_t> b = circle(pts, 17, 1.2, 0.5, 0.3);
  const std::vector<int32_t> tri = bridge_loops(pts, a, b);
  ASSERT_EQ(tri.size(), 3u * (12 + 17));
  std::map<std::pair<int32_t, int32_t>, int> directed;
  for (size_t t = 0; t < tri.size(); t += 3) {
    const Vec3 n = triangle_cross(&pts[3 * size_t(tri[t])], &pts[3 * size_t(tri[t + 1])],
                                  &pts[3 * size_t(tri[t + 2])]);
    EXPECT_GT(norm(n), 1e-6) << "a flat triangle";
    for (int k = 0; k < 3; ++k) ++directed[{tri[t + size_t(k)], tri[t + size_t((k + 1) % 3)]}];
  }
  // Each loop edge once (one direction), each rung twice (both directions).
  auto on = [](const std::vector<int32_t>& loop, int32_t u, int32_t v) {
    for (size_t i = 0; i < loop.size(); ++i)
      if ((loop[i] == u && loop[(i + 1) % loop.size()] == v) ||
          (loop[i] == v && loop[(i + 1) % loop.size()] == u))
        return true;
    return false;
  };
  int loop_edges = 0;
  for (const auto& [e, count] : directed) {
    EXPECT_EQ(count, 1) << "an edge used twice the same way: inconsistent orientation";
    const bool rim = on(a, e.first, e.second) || on(b, e.first, e.second);
    if (rim)
      ++loop_edges;
    else
      EXPECT_EQ(directed.count({e.second, e.first}), 1u) << "a rung used once";
  }
  EXPECT_EQ(loop_edges, 12 + 17);
}

TEST(BridgeLoops, TellsWhetherLoopsRunTheSameWay) {
  std::vector<double> pts;
  const std::vector<int32_t> a = circle(pts, 10, 1.0, 0, 0);
  std::vector<int32_t> b = circle(pts, 14, 1.0, 0.2, 0);
  EXPECT_GT(loops_agreement(pts, a, b), 0);
  std::reverse(b.begin(), b.end());
  EXPECT_LT(loops_agreement(pts, a, b), 0);
}

}  // namespace
}  // namespace vm
