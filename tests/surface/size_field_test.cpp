#include "core/surface/size_field.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "core/mesh/topology.h"
#include "core/phantom/vessel_phantom.h"
#include "tests/support/phantoms.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

constexpr double kPi = std::numbers::pi;

using testing::median;

double distance(const SurfaceMesh& m, int32_t a, int32_t b) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double d = m.points[3 * size_t(a) + k] - m.points[3 * size_t(b) + k];
    d2 += d * d;
  }
  return std::sqrt(d2);
}

// Largest violation of |h_a - h_b| <= g |x_a x_b| over the edges of m.
double worst_gradation_excess(const SurfaceMesh& m, const std::vector<double>& h, double g) {
  double worst = -std::numeric_limits<double>::infinity();
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = m.triangles[3 * t + k], b = m.triangles[3 * t + (k + 1) % 3];
      worst = std::max(worst, std::abs(h[size_t(a)] - h[size_t(b)]) - g * distance(m, a, b));
    }
  return worst;
}

SurfaceMesh noisy_phantom(PhantomKind kind, PhantomTruth* truth = nullptr) {
  PhantomOptions o;
  o.kind = kind;
  o.voxel = 0.1;
  o.noise = 0.3;
  return testing::phantom(o, truth);
}

TEST(SizeField, UniformIsConstant) {
  const SurfaceMesh m = noisy_phantom(PhantomKind::kBifurcation);
  ASSERT_GT(m.num_triangles(), 0u);
  for (double g : {0.0, 0.2, 1.0}) {
    SizeOptions o;
    o.mode = SizeMode::kUniform;
    o.size = 0.37;
    o.gradation = g;
    auto r = vertex_sizes(m, o);
    ASSERT_TRUE(r.ok()) << r.message();
    ASSERT_EQ(r.value().size(), m.num_vertices());
    for (double h : r.value()) ASSERT_EQ(h, 0.37) << "gradation " << g;
  }
}

TEST(SizeField, PerCircumferenceOnACylinderOfKnownRadius) {
  const double R = 1.5;
  const SurfaceMesh tube = testing::open_tube(48, 40, R, 12.0);
  for (double N : {10.0, 24.0}) {
    SizeOptions o;
    o.mode = SizeMode::kPerCircumference;
    o.per_circumference = N;
    o.gradation = 0;
    auto r = vertex_sizes(tube, o);
    ASSERT_TRUE(r.ok()) << r.message();
    ASSERT_EQ(r.value().size(), tube.num_vertices());
    const double expected = 2 * kPi * R / N;
    EXPECT_NEAR(median(r.value()), expected, 0.1 * expected) << "N = " << N;
    for (double h : r.value()) EXPECT_GT(h, 0);
  }
}

TEST(SizeField, PerCircumferenceOnAPhantomMatchesTheTrueRadius) {
  // Near each opening of the noisy tube phantom the true radius is known.
  PhantomTruth truth;
  const SurfaceMesh m = noisy_phantom(PhantomKind::kTube, &truth);
  ASSERT_GT(m.num_triangles(), 0u);
  const double N = 16;
  SizeOptions o;
  o.per_circumference = N;
  o.gradation = 0;
  auto r = vertex_sizes(m, o);
  ASSERT_TRUE(r.ok()) << r.message();
  const TopologyReport topo = analyze_topology(m);
  ASSERT_EQ(int(topo.openings.size()), truth.openings);
  for (const Opening& op : topo.openings) {
    const size_t best = testing::nearest_truth_opening(truth, op.centroid.data());
    const double R = truth.opening_radii[best];
    const std::vector<double> near = testing::rim_band_values(m, op, R, r.value());
    ASSERT_GT(near.size(), 20u);
    const double expected = 2 * kPi * R / N;
    EXPECT_NEAR(median(near), expected, 0.1 * expected) << "opening of radius " << R;
  }
}

// Open cylinder of radius R meshed with near-equilateral triangles: n
// points per ring, alternate rings turned by half a step, rings sqrt(3)/2
// of a step apart (so the edge directions at a vertex are 60 degrees apart).
SurfaceMesh equilateral_cylinder(int n, int rings, double R) {
  SurfaceMesh s;
  const double step = 2 * R * std::sin(kPi / n), dz = step * std::sqrt(3.0) / 2;
  for (int j = 0; j <= rings; ++j)
    for (int i = 0; i < n; ++i) {
      const double a = 2 * kPi * (i + 0.5 * (j % 2)) / n;
      s.points.insert(s.points.end(), {R * std::cos(a), R * std::sin(a), dz * j});
    }
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < n; ++i) {
      const int32_t a = j * n + i, b = j * n + (i + 1) % n;
      const int32_t c = (j + 1) * n + i, d = (j + 1) * n + (i + 1) % n;
      if (j % 2 == 0)  // upper ring turned forward: c sits between a and b
        s.triangles.insert(s.triangles.end(), {a, b, c, b, d, c});
      else  // this ring is turned forward: b sits between c and d
        s.triangles.insert(s.triangles.end(), {a, b, d, a, d, c});
    }
  return s;
}

TEST(SizeField, CurvatureLimitOnACylinder) {
  // kappa_max = 1 / R on a cylinder: h <= 2 pi R / points, reached on a
  // mesh whose edges turn evenly around each vertex.
  const double R = 0.8;
  const SurfaceMesh tube = equilateral_cylinder(64, 40, R);
  ASSERT_EQ(analyze_topology(tube).openings.size(), 2u);
  ASSERT_EQ(analyze_topology(tube).genus, 0);
  SizeOptions o;
  o.mode = SizeMode::kUniform;
  o.size = 10;  // far above the limit
  o.curvature_points = 12;
  o.gradation = 0;
  auto r = vertex_sizes(tube, o);
  ASSERT_TRUE(r.ok()) << r.message();
  const double expected = 2 * kPi * R / 12;
  EXPECT_NEAR(median(r.value()), expected, 0.1 * expected);
  for (double h : r.value()) EXPECT_LE(h, 10.0);
  // On the right-triangle grid of testing::open_tube the edge directions
  // are uneven, so the estimate is only a limit: below the uniform size,
  // positive.
  auto grid = vertex_sizes(testing::open_tube(64, 40, R, 6.0), o);
  ASSERT_TRUE(grid.ok()) << grid.message();
  for (double h : grid.value()) {
    EXPECT_GT(h, 0);
    EXPECT_LT(h, 10.0);
  }
  std::cout << "[ info ] curvature limit 2 pi R / 12 = " << expected << ": median "
            << median(r.value()) << " on the equilateral cylinder, " << median(grid.value())
            << " on the right-triangle grid\n";
}

TEST(SizeField, ClampsAreRespected) {
  const SurfaceMesh m = noisy_phantom(PhantomKind::kBifurcation);
  ASSERT_GT(m.num_triangles(), 0u);
  SizeOptions o;
  o.per_circumference = 12;
  o.gradation = 0;
  auto free = vertex_sizes(m, o);
  ASSERT_TRUE(free.ok()) << free.message();
  // Clamp between the 25th and 75th percentiles of the free field.
  std::vector<double> sorted = free.value();
  std::sort(sorted.begin(), sorted.end());
  o.size_min = sorted[sorted.size() / 4];
  o.size_max = sorted[3 * sorted.size() / 4];
  ASSERT_LT(o.size_min, o.size_max);
  auto clamped = vertex_sizes(m, o);
  ASSERT_TRUE(clamped.ok()) << clamped.message();
  size_t at_min = 0, at_max = 0;
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    const double h = clamped.value()[v];
    EXPECT_GE(h, o.size_min);
    EXPECT_LE(h, o.size_max);
    // Clamping changes nothing else.
    EXPECT_EQ(h, std::clamp(free.value()[v], o.size_min, o.size_max));
    at_min += h == o.size_min;
    at_max += h == o.size_max;
  }
  EXPECT_GT(at_min, 0u);
  EXPECT_GT(at_max, 0u);
  // With gradation the clamps still hold.
  o.gradation = 0.1;
  auto graded = vertex_sizes(m, o);
  ASSERT_TRUE(graded.ok()) << graded.message();
  for (double h : graded.value()) {
    EXPECT_GE(h, o.size_min);
    EXPECT_LE(h, o.size_max);
  }
}

TEST(SizeField, GradationBoundsTheSizeChangeAlongEveryEdge) {
  const SurfaceMesh m = noisy_phantom(PhantomKind::kAneurysm);
  ASSERT_GT(m.num_triangles(), 0u);
  SizeOptions o;
  o.per_circumference = 12;
  o.curvature_points = 8;  // adds local dips that the gradation must spread
  o.gradation = 0;
  auto free = vertex_sizes(m, o);
  ASSERT_TRUE(free.ok()) << free.message();
  // The free field is not graded at this g (else the test proves nothing).
  const double g_tight = 0.05;
  ASSERT_GT(worst_gradation_excess(m, free.value(), g_tight), 1e-6);
  for (double g : {g_tight, 0.3}) {
    o.gradation = g;
    auto r = vertex_sizes(m, o);
    ASSERT_TRUE(r.ok()) << r.message();
    const std::vector<double>& h = r.value();
    ASSERT_EQ(h.size(), m.num_vertices());
    EXPECT_LE(worst_gradation_excess(m, h, g), 1e-12) << "g = " << g;
    // Gradation only lowers sizes, and the smallest size stays.
    for (size_t v = 0; v < h.size(); ++v) {
      EXPECT_LE(h[v], free.value()[v]);
      EXPECT_GT(h[v], 0);
    }
    EXPECT_EQ(*std::min_element(h.begin(), h.end()),
              *std::min_element(free.value().begin(), free.value().end()));
  }
}

TEST(SizeField, LimitGradationSpreadsALocalDipOnly) {
  const SurfaceMesh m = testing::open_tube(32, 16, 1.0, 4.0);
  std::vector<double> h(m.num_vertices(), 0.3);
  h[100] = 0.05;  // a dip, as the fidelity rounds make
  const std::vector<double> before = h;
  ASSERT_GT(worst_gradation_excess(m, h, 0.2), 1e-6);
  limit_gradation(m, h, 0.2);
  EXPECT_LE(worst_gradation_excess(m, h, 0.2), 1e-12);
  size_t lowered = 0;
  for (size_t v = 0; v < h.size(); ++v) {
    EXPECT_LE(h[v], before[v]);
    lowered += h[v] < before[v];
  }
  EXPECT_EQ(h[100], 0.05);
  EXPECT_GT(lowered, 1u);            // spread around the dip
  EXPECT_LT(lowered, h.size() / 4);  // and only there
  std::vector<double> same = before;
  limit_gradation(m, same, 0);  // 0: off
  EXPECT_EQ(same, before);
}

TEST(SizeField, InvalidOptionsAreErrors) {
  const SurfaceMesh tube = testing::open_tube(16, 8);
  auto fails = [&](const SizeOptions& o) { return !vertex_sizes(tube, o).ok(); };
  const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
  auto uniform = [](double size) {
    SizeOptions o;
    o.mode = SizeMode::kUniform;
    o.size = size;
    return o;
  };
  for (double s : {0.0, -1.0, nan, inf}) {
    EXPECT_TRUE(fails(uniform(s))) << "uniform size " << s;
  }
  for (double n : {0.0, -4.0, nan, inf}) {
    SizeOptions o;
    o.per_circumference = n;
    EXPECT_TRUE(fails(o)) << "per circumference " << n;
  }
  {
    SizeOptions o = uniform(0.5);
    o.size_min = 0.4;
    o.size_max = 0.3;
    EXPECT_TRUE(fails(o)) << "min > max";
    o.size_min = -0.1;
    o.size_max = 1;
    EXPECT_TRUE(fails(o)) << "negative min";
    o.size_min = 0;
    o.size_max = 0;
    EXPECT_TRUE(fails(o)) << "zero max";
  }
  for (double g : {-0.1, nan, inf}) {
    SizeOptions o = uniform(0.5);
    o.gradation = g;
    EXPECT_TRUE(fails(o)) << "gradation " << g;
  }
  for (double c : {-1.0, nan, inf}) {
    SizeOptions o = uniform(0.5);
    o.curvature_points = c;
    EXPECT_TRUE(fails(o)) << "curvature points " << c;
  }
  SizeOptions ok;
  ok.mode = SizeMode::kUniform;
  ok.size = 0.5;
  EXPECT_TRUE(vertex_sizes(tube, ok).ok());
  EXPECT_FALSE(vertex_sizes(SurfaceMesh{}, ok).ok()) << "empty mesh";
}

TEST(SizeField, RefinementSpheresLowerTheSizeInsideAndGradeOut) {
  const SurfaceMesh m = noisy_phantom(PhantomKind::kBifurcation);
  SizeOptions o;
  o.mode = SizeMode::kUniform;
  o.size = 0.4;
  o.gradation = 0.2;
  const double c[3] = {m.points[0], m.points[1], m.points[2]};
  o.spheres.push_back({{c[0], c[1], c[2]}, 0.8, 0.05});
  auto r = vertex_sizes(m, o);
  ASSERT_TRUE(r.ok()) << r.message();
  size_t inside = 0;
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    const double d =
        std::hypot(m.points[3 * v] - c[0], m.points[3 * v + 1] - c[1], m.points[3 * v + 2] - c[2]);
    if (d <= 0.8) {
      EXPECT_NEAR(r.value()[v], 0.05, 1e-12);
      ++inside;
    } else {
      // Graded out of the sphere at most at g by distance, and never above h.
      EXPECT_LE(r.value()[v], std::min(0.4, 0.05 + 0.2 * (d - 0.8)) + 1e-12);
    }
    if (d > 0.8 + 0.35 / 0.2 + 0.5) {
      EXPECT_NEAR(r.value()[v], 0.4, 1e-12);
    }
  }
  EXPECT_GT(inside, 10u);
  EXPECT_LE(worst_gradation_excess(m, r.value(), 0.2), 1e-9);
  o.spheres[0].size = 0;
  EXPECT_EQ(vertex_sizes(m, o).status().option(), "refine");
}

}  // namespace
}  // namespace vm
