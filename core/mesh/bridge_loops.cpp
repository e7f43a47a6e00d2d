// Optimal strip between two loops (bridge_loops.h).
#include "core/mesh/bridge_loops.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/geom/vec3.h"

namespace vm {
namespace {

double distance(const std::vector<double>& p, int32_t u, int32_t v) {
  double d[3];
  v3::sub(&p[3 * size_t(u)], &p[3 * size_t(v)], d);
  return v3::norm(d);
}

/// The best strip with rung (a_0, b_s) first and last: the path from (0, 0)
/// to (m, n) through the grid of rungs (a_i mod m, b_(s + j) mod n), each
/// step adding one triangle and one rung. Its cost and triangles.
double strip_from(const std::vector<double>& p, std::span<const int32_t> a,
                  std::span<const int32_t> b, size_t s, std::vector<int32_t>& out) {
  const size_t m = a.size(), n = b.size();
  auto A = [&](size_t i) { return a[i % m]; };
  auto B = [&](size_t j) { return b[(s + j) % n]; };
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> cost((m + 1) * (n + 1), inf);
  std::vector<uint8_t> from((m + 1) * (n + 1), 0);  // 1: came along a, 2: along b
  auto at = [n](size_t i, size_t j) { return i * (n + 1) + j; };
  cost[at(0, 0)] = distance(p, A(0), B(0));
  for (size_t i = 0; i <= m; ++i)
    for (size_t j = 0; j <= n; ++j) {
      if (i == 0 && j == 0) continue;
      const double rung = distance(p, A(i), B(j));
      double best = inf;
      uint8_t how = 0;
      if (i > 0 && cost[at(i - 1, j)] + rung < best) best = cost[at(i - 1, j)] + rung, how = 1;
      if (j > 0 && cost[at(i, j - 1)] + rung < best) best = cost[at(i, j - 1)] + rung, how = 2;
      cost[at(i, j)] = best;
      from[at(i, j)] = how;
    }
  std::vector<std::array<int32_t, 3>> tris;
  for (size_t i = m, j = n; i > 0 || j > 0;) {
    if (from[at(i, j)] == 1) {
      tris.push_back({A(i - 1), A(i), B(j)});
      --i;
    } else {
      tris.push_back({A(i), B(j), B(j - 1)});
      --j;
    }
  }
  out.clear();
  for (auto it = tris.rbegin(); it != tris.rend(); ++it)
    out.insert(out.end(), it->begin(), it->end());
  return cost[at(m, n)];
}

}  // namespace

std::vector<int32_t> bridge_loops(const std::vector<double>& points, std::span<const int32_t> a,
                                  std::span<const int32_t> b, int starts) {
  if (a.size() < 3 || b.size() < 3) return {};
  std::vector<std::pair<double, size_t>> near;
  for (size_t j = 0; j < b.size(); ++j) near.push_back({distance(points, a[0], b[j]), j});
  const size_t k = std::min(near.size(), size_t(std::max(starts, 1)));
  std::partial_sort(near.begin(), near.begin() + long(k), near.end());
  std::vector<int32_t> best, trial;
  double best_cost = std::numeric_limits<double>::infinity();
  for (size_t c = 0; c < k; ++c) {
    const double cost = strip_from(points, a, b, near[c].second, trial);
    if (cost < best_cost) best_cost = cost, best.swap(trial);
  }
  return best;
}

double loops_agreement(const std::vector<double>& points, std::span<const int32_t> a,
                       std::span<const int32_t> b) {
  auto direction = [&](std::span<const int32_t> loop, size_t i) {
    const size_t n = loop.size();
    return at(points, loop[(i + 1) % n]) - at(points, loop[(i + n - 1) % n]);
  };
  double sum = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    size_t nearest = 0;
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < b.size(); ++j) {
      const double d = distance(points, a[i], b[j]);
      if (d < best) best = d, nearest = j;
    }
    sum += dot(normalized(direction(a, i)), normalized(direction(b, nearest)));
  }
  return sum;
}

}  // namespace vm
