#include "core/mesh/edge_geodesics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/mesh/persistent_maxima.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

TEST(EdgeGeodesics, ShortestPathsAlongTheEdgesOfAGrid) {
  const SurfaceMesh grid = testing::square_grid(4);  // 5 x 5 vertices, diagonals (i,j)-(i+1,j+1)
  const VertexGraph g = build_vertex_graph(grid);
  ASSERT_EQ(g.num_vertices(), 25u);
  EXPECT_EQ(g.offsets[1] - g.offsets[0], 3);  // a corner: right, up, diagonal
  const int32_t corner = 0;
  EdgeDijkstra d(g, std::span(&corner, 1));
  d.settle_all();
  EXPECT_NEAR(d.distances()[24], std::sqrt(2.0), 1e-12);                  // along the diagonal
  EXPECT_NEAR(d.distances()[4], 1.0, 1e-12);                              // along the bottom
  EXPECT_NEAR(d.distances()[20 + 2], 0.5 * std::sqrt(2.0) + 0.5, 1e-12);  // (2, 4)
  EXPECT_EQ(d.settled().size(), 25u);
  EXPECT_EQ(d.settled().front(), corner);
}

TEST(EdgeGeodesics, ASearchGrowsAsFarAsAsked) {
  const SurfaceMesh grid = testing::square_grid(8);
  const VertexGraph g = build_vertex_graph(grid);
  const int32_t corner = 0;
  EdgeDijkstra d(g, std::span(&corner, 1));
  const size_t near = d.settle_until(0.3);
  EXPECT_GT(near, 1u);
  EXPECT_LT(near, 81u);
  for (int32_t v : d.settled()) EXPECT_LE(d.distances()[size_t(v)], 0.3);
  EXPECT_LE(d.reach(), 0.3);
  d.settle_all();
  EXPECT_EQ(d.settled().size(), 81u);
  for (size_t i = 1; i < d.settled().size(); ++i)
    EXPECT_LE(d.distances()[size_t(d.settled()[i - 1])], d.distances()[size_t(d.settled()[i])]);
}

TEST(PersistentMaxima, EachMaximumDiesWhereItsRegionMeetsAHigherOne) {
  // A path 0-1-2-3-4-5-6 with values 0 3 1 2 1.5 2.5 0: maxima at 1 (the
  // highest), 5 (joins at 2, value 1 -> persistence 1.5) and 3 (joins 5's
  // region at 4, value 1.5 -> 0.5).
  VertexGraph g;
  g.offsets = {0};
  for (int32_t v = 0; v < 7; ++v) {
    if (v > 0) g.neighbors.push_back(v - 1), g.lengths.push_back(1);
    if (v < 6) g.neighbors.push_back(v + 1), g.lengths.push_back(1);
    g.offsets.push_back(int32_t(g.neighbors.size()));
  }
  const std::vector<double> f = {0, 3, 1, 2, 1.5, 2.5, 0};
  const std::vector<FieldMaximum> all = persistent_maxima(g, f, 0);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].vertex, 1);
  EXPECT_TRUE(std::isinf(all[0].persistence));
  EXPECT_EQ(all[1].vertex, 5);
  EXPECT_DOUBLE_EQ(all[1].persistence, 1.5);
  EXPECT_EQ(all[2].vertex, 3);
  EXPECT_DOUBLE_EQ(all[2].persistence, 0.5);
  EXPECT_EQ(persistent_maxima(g, f, 1.0).size(), 2u);
  // A plateau has one maximum; a non-finite value is left out, which cuts
  // vertex 6 off as a part of its own (its own highest point).
  const std::vector<double> flat = {0, 2, 2, 2, 1, INFINITY, 0};
  const std::vector<FieldMaximum> plateau = persistent_maxima(g, flat, 0);
  ASSERT_EQ(plateau.size(), 2u);
  EXPECT_EQ(plateau[0].vertex, 1);
  EXPECT_EQ(plateau[1].vertex, 6);
  EXPECT_TRUE(std::isinf(plateau[1].persistence));
}

}  // namespace
}  // namespace vm
