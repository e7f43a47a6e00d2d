#include "core/quality/triangle_quality.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace vm {
namespace {

TEST(TriangleQuality, EveryTriangleOfAMesh) {
  SurfaceMesh m;
  m.points = {0, 0, 0, 2, 0, 0, 1, std::sqrt(3.0), 0, 0, 2, 0};
  m.triangles = {0, 1, 2, 0, 2, 3};
  std::vector<float> q = triangle_qualities(m);
  ASSERT_EQ(q.size(), 2u);
  EXPECT_FLOAT_EQ(q[0], float(triangle_gamma(&m.points[0], &m.points[3], &m.points[6])));
  EXPECT_FLOAT_EQ(q[1], float(triangle_gamma(&m.points[0], &m.points[6], &m.points[9])));
  EXPECT_NEAR(q[0], 1.0, 1e-6);
}

TEST(TriangleQuality, StatsAndHistogram) {
  std::vector<float> v = {0.0f, 0.26f, 0.5f, 0.99f, 1.0f};
  QualityStats s = quality_stats(v, 4);
  EXPECT_FLOAT_EQ(float(s.min), 0.0f);
  EXPECT_FLOAT_EQ(float(s.max), 1.0f);
  EXPECT_NEAR(s.mean, (0.26 + 0.5 + 0.99 + 1.0) / 5, 1e-6);
  ASSERT_EQ(s.histogram.size(), 4u);
  EXPECT_EQ(s.histogram[0], 1u);
  EXPECT_EQ(s.histogram[1], 1u);
  EXPECT_EQ(s.histogram[2], 1u);
  EXPECT_EQ(s.histogram[3], 2u);  // 0.99 and 1.0
}

}  // namespace
}  // namespace vm
