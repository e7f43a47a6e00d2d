#include "core/layers/flip_wall_edges.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "core/layers/extrude_layers.h"
#include "core/layers/layer_assembly.h"
#include "core/mesh/volume_check.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

using P = std::array<double, 3>;

TEST(FlipWallEdges, WallFlipKeepsShapeAndQuality) {
  // (a, b, c) and (b, a, d), counterclockwise seen from +z, across the
  // long diagonal ab of a rhombus: the flip to cd betters both.
  const P a{0, 0, 0}, b{2, 0, 0}, c{1, 0.5, 0}, d{1, -0.5, 0};
  EXPECT_TRUE(wall_flip_ok(a.data(), b.data(), c.data(), d.data()));
  // Back to the long diagonal: gamma_k 0.99 -> 0.38, refused.
  EXPECT_FALSE(wall_flip_ok(d.data(), c.data(), a.data(), b.data()));
  // A quad not convex at b: the new pair would fold.
  const P d2{2.5, -0.1, 0};
  EXPECT_FALSE(wall_flip_ok(a.data(), b.data(), c.data(), d2.data()));
  // Far from planar: the diagonals 0.31 apart, more than 0.1 of cd.
  const P c3{1, 0.5, 0.8};
  EXPECT_FALSE(wall_flip_ok(a.data(), b.data(), c3.data(), d.data()));
  // Slightly bent (well within 0.1 of cd): allowed.
  const P c4{1, 0.5, 0.05};
  EXPECT_TRUE(wall_flip_ok(a.data(), b.data(), c4.data(), d.data()));
}

TEST(FlipWallEdges, LayerColumnsFlipWithTheWall) {
  const SurfaceMesh wall = testing::open_tube(24, 10, 1.0, 2.0);
  for (bool outward : {false, true}) {
    SCOPED_TRACE(outward ? "outward" : "inward");
    LayerSpec spec;
    spec.outward = outward;
    auto r = extrude_layers(wall, std::vector<double>(wall.num_vertices(), 1.0), spec);
    ASSERT_TRUE(r.ok()) << r.message();
    const LayerMesh& m = r.value();
    // An inner wall edge: triangles t (a, b, c) and u (b, a, d).
    const std::vector<int32_t>& w = wall.triangles;
    int32_t a = -1, b = -1, c = -1, d = -1;
    size_t t = 0, u = 0;
    for (t = 0; t < wall.num_triangles() && d < 0; ++t)
      for (u = 0; u < wall.num_triangles() && d < 0; ++u)
        for (int i = 0; i < 3 && d < 0; ++i)
          for (int j = 0; j < 3 && d < 0; ++j)
            if (w[3 * t + size_t(i)] == w[3 * u + size_t((j + 1) % 3)] &&
                w[3 * t + size_t((i + 1) % 3)] == w[3 * u + size_t(j)]) {
              a = w[3 * t + size_t(i)], b = w[3 * t + size_t((i + 1) % 3)];
              c = w[3 * t + size_t((i + 2) % 3)], d = w[3 * u + size_t((j + 2) % 3)];
            }
    ASSERT_GE(d, 0);
    --t, --u;
    EXPECT_TRUE(layer_flip_ok(m, a, b, c, d));
    EXPECT_FALSE(layer_flip_ok(m, a, b, d, c));  // the pair turned over
    std::vector<int32_t> flipped = w;
    std::copy_n(std::array<int32_t, 3>{c, a, d}.begin(), 3, flipped.begin() + long(3 * t));
    std::copy_n(std::array<int32_t, 3>{d, b, c}.begin(), 3, flipped.begin() + long(3 * u));
    const LayerMesh f = retriangulate_layer(m, flipped);
    EXPECT_EQ(f.num_prisms(), m.num_prisms());
    EXPECT_EQ(f.points, m.points);
    const auto check = check_volume_mesh(layer_volume(f, true));
    EXPECT_TRUE(check.ok()) << check.message();
  }
}

TEST(FlipWallEdges, RuleOnlyWhereTheWallIsTheCoresBoundaryOrPrismsAreKept) {
  const SurfaceMesh wall = testing::open_tube(24, 10, 1.0, 2.0);
  auto r = extrude_layers(wall, std::vector<double>(wall.num_vertices(), 1.0), LayerSpec{});
  ASSERT_TRUE(r.ok()) << r.message();
  const LayerMesh& m = r.value();
  EXPECT_FALSE(wall_flip_rule(&m, nullptr, {}, 0, false));  // the top slice takes them
  const auto kept = wall_flip_rule(&m, nullptr, {}, 0, true);
  ASSERT_TRUE(kept);
  const auto bare = wall_flip_rule(nullptr, nullptr, wall.points, wall.num_vertices(), false);
  ASSERT_TRUE(bare);
  // The tube's first quad, triangles (0, 1, n + 1) and (0, n + 1, n): its
  // diagonal (n + 1, 0) flipped to (1, n) is fine on the wall and in the
  // layer.
  const int32_t n = 24;
  const int32_t a = n + 1, b = 0, c = 1, d = n;
  ASSERT_TRUE(wall_flip_ok(&wall.points[3 * a], &wall.points[3 * b], &wall.points[3 * c],
                           &wall.points[3 * d]));
  EXPECT_TRUE(bare(a, b, c, d, 0));
  EXPECT_TRUE(kept(a, b, c, d, 0));
  EXPECT_FALSE(bare(a, b, c, d, 1));                             // a cap's
  EXPECT_FALSE(bare(a, b, c, int32_t(wall.num_vertices()), 0));  // not a wall vertex
}

}  // namespace
}  // namespace vm
