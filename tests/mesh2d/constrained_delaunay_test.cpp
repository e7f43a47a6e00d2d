#include "core/mesh2d/constrained_delaunay.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <set>

#include "core/geom/predicates.h"

namespace vm {
namespace {

const double* P(const Mesh2D& m, int32_t v) { return &m.points[2 * size_t(v)]; }

double area(const Mesh2D& m) {
  double a = 0;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const double *p = P(m, m.triangles[3 * t]), *q = P(m, m.triangles[3 * t + 1]),
                 *r = P(m, m.triangles[3 * t + 2]);
    a += 0.5 * ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]));
  }
  return a;
}

using Edge = std::pair<int32_t, int32_t>;
Edge key(int32_t a, int32_t b) { return {std::min(a, b), std::max(a, b)}; }

// Checks orientation, conformity (each edge in at most 2 triangles, with
// opposite directions), and the local Delaunay property of every edge that
// is not a constraint.
void expect_valid_cdt(const Mesh2D& m, const std::set<Edge>& constraints) {
  std::map<Edge, std::vector<std::pair<size_t, int>>> edges;  // -> (tri, opposite corner)
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t* v = &m.triangles[3 * t];
    ASSERT_GT(orient2d(P(m, v[0]), P(m, v[1]), P(m, v[2])), 0) << "triangle " << t;
    for (int k = 0; k < 3; ++k) edges[key(v[(k + 1) % 3], v[(k + 2) % 3])].push_back({t, k});
  }
  for (auto& [e, uses] : edges) {
    ASSERT_LE(uses.size(), 2u);
    if (uses.size() < 2) continue;
    const int32_t* a = &m.triangles[3 * uses[0].first];
    const int32_t* b = &m.triangles[3 * uses[1].first];
    // Opposite directions.
    EXPECT_EQ(a[(uses[0].second + 1) % 3], b[(uses[1].second + 2) % 3]);
    if (constraints.count(e)) continue;
    int32_t q = b[uses[1].second];
    EXPECT_LE(incircle(P(m, a[0]), P(m, a[1]), P(m, a[2]), P(m, q)), 0)
        << "edge " << e.first << "-" << e.second << " is not locally Delaunay";
  }
  for (const Edge& c : constraints) EXPECT_TRUE(edges.count(c)) << c.first << "-" << c.second;
}

TEST(ConstrainedDelaunay, RandomPointsGiveTheDelaunayTriangulation) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> pts;
  for (int i = 0; i < 500; ++i) pts.insert(pts.end(), {u(rng), u(rng)});
  auto r = constrained_delaunay(pts, {});
  ASSERT_TRUE(r.ok()) << r.message();
  expect_valid_cdt(r.value(), {});
  // Empty circumcircles against all points (global Delaunay).
  const Mesh2D& m = r.value();
  for (size_t t = 0; t < m.num_triangles(); t += 7)
    for (size_t v = 0; v < m.num_vertices(); ++v)
      ASSERT_LE(incircle(P(m, m.triangles[3 * t]), P(m, m.triangles[3 * t + 1]),
                         P(m, m.triangles[3 * t + 2]), P(m, int32_t(v))),
                0);
  // Triangles of a point set: 2n - 2 - h, h hull vertices; check via area
  // of the convex hull being covered and Euler on the result.
  std::set<Edge> all;
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k)
      all.insert(key(m.triangles[3 * t + k], m.triangles[3 * t + (k + 1) % 3]));
  EXPECT_EQ(long(m.num_vertices()) - long(all.size()) + long(m.num_triangles()), 1);
}

TEST(ConstrainedDelaunay, CocircularGridIsHandled) {
  // A regular grid: every cell is cocircular, the worst case for the
  // incircle test.
  std::vector<double> pts;
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 20; ++i) pts.insert(pts.end(), {0.1 * i, 0.1 * j});
  auto r = constrained_delaunay(pts, {});
  ASSERT_TRUE(r.ok()) << r.message();
  expect_valid_cdt(r.value(), {});
  EXPECT_EQ(r.value().num_triangles(), 2u * 19 * 19);
  EXPECT_NEAR(area(r.value()), 1.9 * 1.9, 1e-12);
}

TEST(ConstrainedDelaunay, SquareWithAHoleAndInteriorPoints) {
  std::vector<double> pts = {0, 0, 4, 0, 4, 4, 0, 4,   // outer
                             1, 1, 1, 3, 3, 3, 3, 1};  // hole (any direction)
  std::vector<int32_t> seg = {0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4};
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(0.05, 3.95);
  while (pts.size() < 2 * 200) {
    double x = u(rng), y = u(rng);
    if (x > 0.9 && x < 3.1 && y > 0.9 && y < 3.1) continue;  // not in the hole
    pts.insert(pts.end(), {x, y});
  }
  auto r = constrained_delaunay(pts, seg);
  ASSERT_TRUE(r.ok()) << r.message();
  std::set<Edge> cons;
  for (size_t i = 0; i < seg.size(); i += 2) cons.insert(key(seg[i], seg[i + 1]));
  expect_valid_cdt(r.value(), cons);
  EXPECT_NEAR(area(r.value()), 16 - 4, 1e-9);
}

TEST(ConstrainedDelaunay, LongSegmentsThroughManyTrianglesAreRecovered) {
  // A thin, long polygon (zig-zag) over a dense random cloud: its edges cut
  // many Delaunay edges and must be forced in by flips.
  std::vector<double> pts;
  const int n = 12;
  for (int i = 0; i < n; ++i) pts.insert(pts.end(), {double(i), (i % 2) * 0.3});
  for (int i = n - 1; i >= 0; --i) pts.insert(pts.end(), {double(i), 2.0 + (i % 2) * 0.3});
  std::vector<int32_t> seg;
  for (int i = 0; i < 2 * n; ++i) seg.insert(seg.end(), {i, (i + 1) % (2 * n)});
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> ux(-1, double(n)), uy(-1, 3.5);
  for (int i = 0; i < 400; ++i) pts.insert(pts.end(), {ux(rng), uy(rng)});
  auto r = constrained_delaunay(pts, seg);
  ASSERT_TRUE(r.ok()) << r.message();
  std::set<Edge> cons;
  for (size_t i = 0; i < seg.size(); i += 2) cons.insert(key(seg[i], seg[i + 1]));
  expect_valid_cdt(r.value(), cons);
  // Area of the zig-zag polygon (shoelace).
  double a = 0;
  for (int i = 0; i < 2 * n; ++i) {
    int j = (i + 1) % (2 * n);
    a += pts[2 * i] * pts[2 * j + 1] - pts[2 * j] * pts[2 * i + 1];
  }
  EXPECT_NEAR(area(r.value()), std::fabs(a) / 2, 1e-9);
}

TEST(ConstrainedDelaunay, RandomStarPolygonsWithHolesAndDenseInteriors) {
  // Star-shaped outer loops with a small square hole and many interior
  // points, over 20 seeds: conformity, Delaunay edges, exact area.
  for (uint32_t seed = 0; seed < 20; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> ur(0.6, 1.0), u(-1, 1);
    const int n = 40 + int(seed) * 7;
    std::vector<double> pts;
    std::vector<int32_t> seg;
    for (int i = 0; i < n; ++i) {
      double a = 2 * std::numbers::pi * i / n, r = ur(rng);
      pts.insert(pts.end(), {r * std::cos(a), r * std::sin(a)});
      seg.insert(seg.end(), {i, (i + 1) % n});
    }
    const double h = 0.15;
    pts.insert(pts.end(), {-h, -h, h, -h, h, h, -h, h});
    for (int i = 0; i < 4; ++i) seg.insert(seg.end(), {n + i, n + (i + 1) % 4});
    double outer = 0;
    for (int i = 0; i < n; ++i) {
      int j = (i + 1) % n;
      outer += pts[2 * i] * pts[2 * j + 1] - pts[2 * j] * pts[2 * i + 1];
    }
    for (int i = 0; i < 600; ++i) {
      double x = 0.55 * u(rng), y = 0.55 * u(rng);
      if (std::fabs(x) < h && std::fabs(y) < h) continue;
      pts.insert(pts.end(), {x, y});
    }
    auto r = constrained_delaunay(pts, seg);
    ASSERT_TRUE(r.ok()) << "seed " << seed << ": " << r.message();
    std::set<Edge> cons;
    for (size_t i = 0; i < seg.size(); i += 2) cons.insert(key(seg[i], seg[i + 1]));
    expect_valid_cdt(r.value(), cons);
    EXPECT_NEAR(area(r.value()), outer / 2 - 4 * h * h, 1e-9) << "seed " << seed;
  }
}

TEST(ConstrainedDelaunay, CollinearPointsOnASegmentSplitIt) {
  // Points exactly on a boundary segment: the segment becomes a chain.
  std::vector<double> pts = {0, 0, 1, 0, 1, 1, 0, 1, 0.25, 0, 0.5, 0, 0.75, 0, 0.5, 0.5};
  std::vector<int32_t> seg = {0, 1, 1, 2, 2, 3, 3, 0};
  auto r = constrained_delaunay(pts, seg);
  ASSERT_TRUE(r.ok()) << r.message();
  std::set<Edge> cons = {key(0, 4), key(4, 5), key(5, 6), key(6, 1),
                         key(1, 2), key(2, 3), key(3, 0)};
  expect_valid_cdt(r.value(), cons);
  EXPECT_NEAR(area(r.value()), 1.0, 1e-12);
}

TEST(ConstrainedDelaunay, CrossingSegmentsAreRefused) {
  std::vector<double> pts = {0, 0, 1, 1, 0, 1, 1, 0, 0.5, -1};
  auto r = constrained_delaunay(pts, {0, 1, 2, 3});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("cross"), std::string::npos);
  EXPECT_FALSE(constrained_delaunay(pts, {0, 9}).ok());
}

TEST(ConstrainedDelaunay, DuplicatePointsAreMerged) {
  std::vector<double> pts = {0, 0, 1, 0, 0, 1, 1, 0, 1, 1};
  auto r = constrained_delaunay(pts, {});
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.value().num_triangles(), 2u);
  expect_valid_cdt(r.value(), {});
}

}  // namespace
}  // namespace vm
