#include "core/mesh2d/optimize2d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "core/geom/predicates.h"
#include "core/mesh2d/delaunay_refinement.h"
#include "core/quality/triangle_quality.h"
#include "tests/mesh2d/mesh2d_test_shapes.h"

namespace vm {
namespace {

struct Q {
  double min = 1, mean = 0, area = 0;
};

Q quality(const Mesh2D& m) {
  Q q;
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    double p[3][3];
    for (int k = 0; k < 3; ++k)
      p[k][0] = m.points[2 * size_t(m.triangles[3 * t + k])],
      p[k][1] = m.points[2 * size_t(m.triangles[3 * t + k]) + 1], p[k][2] = 0;
    EXPECT_GT(orient2d(p[0], p[1], p[2]), 0) << "triangle " << t;
    double g = triangle_gamma(p[0], p[1], p[2]);
    q.min = std::min(q.min, g);
    q.mean += g / double(m.num_triangles());
    q.area += 0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) -
                     (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]));
  }
  return q;
}

std::map<std::pair<int32_t, int32_t>, int> boundary_edges(const Mesh2D& m) {
  std::map<std::pair<int32_t, int32_t>, int> count;
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k)
      ++count[std::minmax(m.triangles[3 * t + k], m.triangles[3 * t + (k + 1) % 3])];
  std::map<std::pair<int32_t, int32_t>, int> b;
  for (auto& [e, n] : count)
    if (n == 1) b[e] = 1;
  return b;
}

TEST(Optimize2D, ImprovesARefinedAnnulusAndKeepsItsBoundary) {
  const int n_out = 80, n_in = 30;
  std::vector<double> pts;
  std::vector<int32_t> seg;
  testing::annulus(n_out, n_in, 0.4, pts, seg);
  auto r = delaunay_refinement(pts, seg, [](double u, double) { return 0.07 + 0.02 * u; });
  ASSERT_TRUE(r.ok()) << r.message();
  Mesh2D m = r.value();
  Q before = quality(m);
  auto boundary = boundary_edges(m);
  std::vector<double> boundary_points(m.points.begin(), m.points.begin() + 2 * (n_out + n_in));
  Optimize2DStats s = optimize_mesh2d(m);
  Q after = quality(m);
  EXPECT_GT(s.moves, 0u);
  EXPECT_NEAR(after.area, before.area, 1e-12);
  EXPECT_GE(after.min, before.min - 1e-12);
  EXPECT_GT(after.mean, before.mean + 0.01);
  EXPECT_EQ(boundary_edges(m), boundary);
  EXPECT_EQ(std::vector<double>(m.points.begin(), m.points.begin() + 2 * (n_out + n_in)),
            boundary_points);
  std::cout << "[ info ] annulus: gamma min " << before.min << " -> " << after.min << ", mean "
            << before.mean << " -> " << after.mean << " (" << s.moves << " moves, " << s.flips
            << " flips)\n";
}

}  // namespace
}  // namespace vm
