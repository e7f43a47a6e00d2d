#include "core/layers/refine_layers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "core/layers/extrude_layers.h"
#include "core/mesh/volume_check.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

// 1-to-4 subdivision of every wall triangle of m, the edge midpoints taken
// on layer `at_layer` (as a boundary recovery would split the front).
struct Subdivision {
  std::vector<int32_t> triangles, parent;
  std::vector<double> new_points;
};
Subdivision subdivide(const LayerMesh& m, int at_layer) {
  Subdivision s;
  const int32_t nv = int32_t(m.wall_vertices), top = m.layer_vertex(0, m.layers);
  std::map<std::pair<int32_t, int32_t>, int32_t> mid;
  auto midpoint = [&](int32_t a, int32_t b) {
    const auto key = std::minmax(a, b);
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    const int32_t id = nv + int32_t(s.new_points.size() / 3);
    const double* p = &m.points[3 * size_t(m.layer_vertex(a, at_layer))];
    const double* q = &m.points[3 * size_t(m.layer_vertex(b, at_layer))];
    for (int k = 0; k < 3; ++k) s.new_points.push_back(0.5 * (p[k] + q[k]));
    mid[key] = id;
    return id;
  };
  for (size_t t = 0; t < m.wall_triangles; ++t) {
    const int32_t a = m.front[3 * t] - top, b = m.front[3 * t + 1] - top,
                  c = m.front[3 * t + 2] - top;
    const int32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    s.triangles.insert(s.triangles.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
    s.parent.insert(s.parent.end(), 4, int32_t(t));
  }
  return s;
}

TEST(RefineLayers, SubdividedTubeStaysValidAndPlanar) {
  const SurfaceMesh wall = testing::open_tube(24, 10, 1.0, 2.0);
  for (bool outward : {false, true}) {
    for (int at_layer : {0, 4}) {
      SCOPED_TRACE(std::string(outward ? "outward" : "inward") + " at layer " +
                   std::to_string(at_layer));
      LayerSpec spec;
      spec.outward = outward;
      auto r = extrude_layers(wall, std::vector<double>(wall.num_vertices(), 1.0), spec);
      ASSERT_TRUE(r.ok()) << r.message();
      const LayerMesh& m = r.value();
      const Subdivision s = subdivide(m, at_layer);
      auto refined = refine_layer_columns(m, s.triangles, s.parent, s.new_points, at_layer);
      ASSERT_TRUE(refined.ok()) << refined.message();
      const LayerMesh& f = refined.value();
      EXPECT_EQ(f.wall_triangles, 4 * m.wall_triangles);
      EXPECT_EQ(f.wall_vertices, m.wall_vertices + s.new_points.size() / 3);
      // The given points are used exactly on their layer.
      for (size_t j = 0; j < s.new_points.size() / 3; ++j)
        for (int k = 0; k < 3; ++k)
          EXPECT_EQ(f.points[3 * size_t(f.layer_vertex(int32_t(m.wall_vertices + j), at_layer)) +
                             size_t(k)],
                    s.new_points[3 * j + size_t(k)]);
      // Conforming, positive, boundary = wall + front + rings.
      const auto check = check_volume_mesh(layer_volume(f, true));
      EXPECT_TRUE(check.ok()) << check.message();
      // Same volume as before refinement (the prisms are cut, not moved).
      const auto before = check_volume_mesh(layer_volume(m, true));
      ASSERT_TRUE(before.ok());
      if (check.ok()) {
        EXPECT_NEAR(check.value().volume, before.value().volume, 1e-9);
      }
      // Rims doubled, still planar.
      ASSERT_EQ(f.openings.size(), 2u);
      for (size_t o = 0; o < 2; ++o) {
        EXPECT_EQ(f.openings[o].rim.size(), 2 * m.openings[o].rim.size());
        for (int32_t id : f.openings[o].columns) {
          double d = 0;
          for (int k = 0; k < 3; ++k)
            d += (f.points[3 * size_t(id) + size_t(k)] - f.openings[o].origin[k]) *
                 f.openings[o].normal[k];
          EXPECT_LE(std::abs(d), 1e-12);
        }
      }
    }
  }
}

TEST(RefineLayers, Errors) {
  const SurfaceMesh wall = testing::open_tube(12, 4, 1.0, 1.0);
  auto r = extrude_layers(wall, std::vector<double>(wall.num_vertices(), 1.0), LayerSpec{});
  ASSERT_TRUE(r.ok());
  const LayerMesh& m = r.value();
  const Subdivision s = subdivide(m, 4);
  EXPECT_FALSE(refine_layer_columns(m, s.triangles, {0}, s.new_points, 4).ok());
  EXPECT_FALSE(refine_layer_columns(m, s.triangles, s.parent, s.new_points, 7).ok());
  std::vector<double> extra = s.new_points;
  extra.insert(extra.end(), {0, 0, 0});  // a column in no triangle
  EXPECT_FALSE(refine_layer_columns(m, s.triangles, s.parent, extra, 4).ok());
  std::vector<int32_t> bad = s.triangles;
  bad[0] = int32_t(m.wall_vertices + s.new_points.size());  // out of range
  EXPECT_FALSE(refine_layer_columns(m, bad, s.parent, s.new_points, 4).ok());
}

}  // namespace
}  // namespace vm
