#include "core/mesh2d/delaunay_refinement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include "core/geom/predicates.h"
#include "core/quality/triangle_quality.h"
#include "tests/mesh2d/mesh2d_test_shapes.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

struct Stats {
  double area = 0, min_angle = 180, min_gamma = 1, mean_gamma = 0;
  std::vector<double> edge_lengths;
};

Stats stats_of(const Mesh2D& m) {
  Stats s;
  std::set<std::pair<int32_t, int32_t>> edges;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const int32_t* v = &m.triangles[3 * t];
    double p[3][3];
    for (int k = 0; k < 3; ++k)
      p[k][0] = m.points[2 * v[k]], p[k][1] = m.points[2 * v[k] + 1], p[k][2] = 0;
    EXPECT_GT(orient2d(p[0], p[1], p[2]), 0);
    s.area += 0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) -
                     (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]));
    double g = triangle_gamma(p[0], p[1], p[2]);
    s.min_gamma = std::min(s.min_gamma, g);
    s.mean_gamma += g / double(m.num_triangles());
    for (int k = 0; k < 3; ++k) {
      const double *a = p[k], *b = p[(k + 1) % 3], *c = p[(k + 2) % 3];
      double ux = b[0] - a[0], uy = b[1] - a[1], wx = c[0] - a[0], wy = c[1] - a[1];
      double ang =
          std::atan2(std::fabs(ux * wy - uy * wx), ux * wx + uy * wy) * 180 / std::numbers::pi;
      s.min_angle = std::min(s.min_angle, ang);
      auto e = std::minmax(v[k], v[(k + 1) % 3]);
      if (edges.insert(e).second) s.edge_lengths.push_back(std::hypot(ux, uy));
    }
  }
  return s;
}

using testing::median;

// Square [0, L]^2 with its boundary split every `h`.
void square(double L, double h, std::vector<double>& pts, std::vector<int32_t>& seg) {
  int n = int(std::round(L / h));
  for (int side = 0; side < 4; ++side)
    for (int i = 0; i < n; ++i) {
      double t = L * i / n;
      double xy[4][2] = {{t, 0}, {L, t}, {L - t, L}, {0, L - t}};
      pts.insert(pts.end(), {xy[side][0], xy[side][1]});
    }
  int32_t m = 4 * n, base = int32_t(seg.empty() ? 0 : pts.size() / 2 - m);
  for (int32_t i = 0; i < m; ++i) seg.insert(seg.end(), {base + i, base + (i + 1) % m});
}

TEST(DelaunayRefinement, UniformSizeOnASquare) {
  std::vector<double> pts;
  std::vector<int32_t> seg;
  const double h = 0.05;
  square(1.0, h, pts, seg);
  const size_t boundary = pts.size() / 2;
  auto r = delaunay_refinement(pts, seg, [&](double, double) { return h; });
  ASSERT_TRUE(r.ok()) << r.message();
  Stats s = stats_of(r.value());
  EXPECT_NEAR(s.area, 1.0, 1e-12);
  EXPECT_NEAR(median(s.edge_lengths), h, 0.15 * h);
  EXPECT_GT(s.min_angle, 20.0);
  EXPECT_GT(s.min_gamma, 0.45);
  EXPECT_GT(s.mean_gamma, 0.85);
  // The boundary is frozen: the input points come first and are unchanged,
  // and no inserted point lies on the boundary.
  for (size_t i = 0; i < 2 * boundary; ++i) EXPECT_EQ(r.value().points[i], pts[i]);
  for (size_t v = boundary; v < r.value().num_vertices(); ++v) {
    double x = r.value().points[2 * v], y = r.value().points[2 * v + 1];
    EXPECT_TRUE(x > 0 && x < 1 && y > 0 && y < 1) << x << " " << y;
  }
  std::cout << "[ info ] square h=0.05: " << r.value().num_triangles() << " triangles, min angle "
            << s.min_angle << ", gamma min " << s.min_gamma << " mean " << s.mean_gamma << "\n";
}

TEST(DelaunayRefinement, GradedSizeIsFollowed) {
  std::vector<double> pts;
  std::vector<int32_t> seg;
  square(1.0, 0.02, pts, seg);
  auto size = [](double u, double) { return 0.02 + 0.1 * u; };
  auto r = delaunay_refinement(pts, seg, size);
  ASSERT_TRUE(r.ok()) << r.message();
  // Edges in the right tenth are much longer than in the left tenth.
  const Mesh2D& m = r.value();
  std::vector<double> left, right;
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      int32_t a = m.triangles[3 * t + k], b = m.triangles[3 * t + (k + 1) % 3];
      double mx = 0.5 * (m.points[2 * a] + m.points[2 * b]);
      double len =
          std::hypot(m.points[2 * a] - m.points[2 * b], m.points[2 * a + 1] - m.points[2 * b + 1]);
      if (mx < 0.1) left.push_back(len);
      if (mx > 0.8 && mx < 0.9) right.push_back(len);
    }
  EXPECT_NEAR(median(right), size(0.85, 0), 0.3 * size(0.85, 0));
  EXPECT_LT(median(left), 0.5 * median(right));
  EXPECT_NEAR(stats_of(m).area, 1.0, 1e-12);
}

TEST(DelaunayRefinement, AnnulusKeepsItsHole) {
  const int n_out = 64, n_in = 26;
  std::vector<double> pts;
  std::vector<int32_t> seg;
  testing::annulus(n_out, n_in, 0.4, pts, seg);
  auto r = delaunay_refinement(pts, seg, [](double, double) { return 0.1; });
  ASSERT_TRUE(r.ok()) << r.message();
  double outer = 0.5 * n_out * std::sin(2 * std::numbers::pi / n_out);
  double inner = 0.5 * n_in * 0.16 * std::sin(2 * std::numbers::pi / n_in);
  Stats s = stats_of(r.value());
  EXPECT_NEAR(s.area, outer - inner, 1e-12);
  EXPECT_GT(s.min_angle, 20.0);
}

TEST(DelaunayRefinement, SizeMuchFinerThanTheBoundaryTerminates) {
  // Boundary every 0.1, size 0.025: the boundary cannot follow, the
  // interior does; the refinement ends with a valid mesh (points that would
  // encroach the boundary are rejected instead of piling up along it).
  std::vector<double> pts;
  std::vector<int32_t> seg;
  square(1.0, 0.1, pts, seg);
  auto r = delaunay_refinement(pts, seg, [](double, double) { return 0.025; });
  ASSERT_TRUE(r.ok()) << r.message();
  Stats s = stats_of(r.value());
  EXPECT_NEAR(s.area, 1.0, 1e-12);
  EXPECT_GT(r.value().num_triangles(), 2000u);
  EXPECT_LT(r.value().num_triangles(), 20000u);
}

TEST(DelaunayRefinement, RefusesANonPositiveSize) {
  std::vector<double> pts;
  std::vector<int32_t> seg;
  square(1.0, 0.25, pts, seg);
  auto r = delaunay_refinement(pts, seg, [](double, double) { return 0.0; });
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("positive"), std::string::npos);
}

}  // namespace
}  // namespace vm
