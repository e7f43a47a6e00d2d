#include "core/mesh/tet_face_adjacency.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <random>
#include <vector>

#include "core/volume/delaunay3d.h"
#include "tests/support/volume_inputs.h"

namespace vm {
namespace {

/// The sorted vertices of face f (opposite vertex f) of tetrahedron t.
std::array<int32_t, 3> face_of(const std::vector<int32_t>& tets, size_t t, int f) {
  std::array<int32_t, 3> k{};
  for (int s = 0, n = 0; s < 4; ++s)
    if (s != f) k[size_t(n++)] = tets[4 * t + size_t(s)];
  std::sort(k.begin(), k.end());
  return k;
}

/// Brute force: every pair of faces compared.
std::vector<int32_t> brute_force(const std::vector<int32_t>& tets) {
  const size_t nf = tets.size();
  std::vector<int32_t> across(nf, kNoTetAcross);
  for (size_t a = 0; a < nf; ++a)
    for (size_t b = 0; b < nf; ++b)
      if (a / 4 != b / 4 && face_of(tets, a / 4, int(a % 4)) == face_of(tets, b / 4, int(b % 4)))
        across[a] = int32_t(b);
  return across;
}

// Three tetrahedra around the edge (0, 1) (ring 2, 3, 4) and a fourth glued
// on face (1, 2, 3) of the first:
//   t0 = (0, 1, 2, 3), t1 = (0, 1, 3, 4), t2 = (0, 1, 4, 2), t3 = (5, 1, 3, 2)
const std::vector<int32_t> kFan = {0, 1, 2, 3, 0, 1, 3, 4, 0, 1, 4, 2, 5, 1, 3, 2};

TEST(TetFaceAdjacency, SmallMeshHasTheKnownNeighbours) {
  auto r = tet_face_adjacency(kFan.data(), 4, 6);
  ASSERT_TRUE(r.ok()) << r.message();
  const std::vector<int32_t>& a = r.value();
  ASSERT_EQ(a.size(), 16u);
  // t0: face 0 (1,2,3) -> t3 face 0 (1,3,2); face 1 (0,2,3) boundary;
  // face 2 (0,1,3) -> t1 face 3 (0,1,3); face 3 (0,1,2) -> t2 face 2 (0,1,2).
  EXPECT_EQ(a[0], 4 * 3 + 0);
  EXPECT_EQ(a[1], kNoTetAcross);
  EXPECT_EQ(a[2], 4 * 1 + 3);
  EXPECT_EQ(a[3], 4 * 2 + 2);
  // t1 (0,1,3,4): face 0 (1,3,4) and face 1 (0,3,4) boundary; face 2
  // (0,1,4) -> t2 face 3 (0,1,4); face 3 -> t0 face 2.
  EXPECT_EQ(a[4], kNoTetAcross);
  EXPECT_EQ(a[5], kNoTetAcross);
  EXPECT_EQ(a[6], 4 * 2 + 3);
  EXPECT_EQ(a[7], 4 * 0 + 2);
  // t2 (0,1,4,2): faces 0, 1 boundary; face 2 -> t0 face 3; face 3 -> t1 face 2.
  EXPECT_EQ(a[8], kNoTetAcross);
  EXPECT_EQ(a[9], kNoTetAcross);
  EXPECT_EQ(a[10], 4 * 0 + 3);
  EXPECT_EQ(a[11], 4 * 1 + 2);
  // t3 (5,1,3,2): face 0 -> t0 face 0, the rest boundary.
  EXPECT_EQ(a[12], 4 * 0 + 0);
  EXPECT_EQ(a[13], kNoTetAcross);
  EXPECT_EQ(a[14], kNoTetAcross);
  EXPECT_EQ(a[15], kNoTetAcross);
  EXPECT_EQ(a, brute_force(kFan));
}

TEST(TetFaceAdjacency, OneTetrahedronIsAllBoundary) {
  const std::vector<int32_t> one = {3, 1, 0, 2};
  auto r = tet_face_adjacency(one.data(), 1, 4);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.value(), std::vector<int32_t>(4, kNoTetAcross));
  auto empty = tet_face_adjacency(nullptr, 0, 0);
  ASSERT_TRUE(empty.ok());
  EXPECT_TRUE(empty.value().empty());
}

TEST(TetFaceAdjacency, RejectsBadIndicesAndFacesOfThreeTetrahedra) {
  const std::vector<int32_t> bad = {0, 1, 2, 7};
  EXPECT_FALSE(tet_face_adjacency(bad.data(), 1, 4).ok());
  const std::vector<int32_t> negative = {0, 1, -1, 2};
  EXPECT_FALSE(tet_face_adjacency(negative.data(), 1, 4).ok());
  // Face (0, 1, 2) in three tetrahedra.
  const std::vector<int32_t> three = {0, 1, 2, 3, 2, 1, 0, 4, 0, 2, 1, 5};
  auto r = tet_face_adjacency(three.data(), 3, 6);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("more than two"), std::string::npos) << r.message();
}

TEST(TetFaceAdjacency, RandomDelaunayMeshMatchesBruteForce) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    auto d = Delaunay3D::build(testing::random_cube_points(60, seed));
    ASSERT_TRUE(d.ok()) << d.message();
    std::vector<int32_t> tets = d.value().finite_tets();
    const size_t nv = d.value().points().size() / 3;
    // Shuffled tetrahedra and rotated vertices within each (an even
    // permutation keeps them positive), so no order is assumed.
    std::mt19937 rng(seed);
    std::vector<size_t> order(tets.size() / 4);
    std::iota(order.begin(), order.end(), size_t(0));
    std::shuffle(order.begin(), order.end(), rng);
    std::vector<int32_t> shuffled;
    for (size_t t : order) {
      const int32_t* v = &tets[4 * t];
      const int r = int(rng() % 3);  // (0,1,2,3) -> a 3-cycle of the last three
      const int32_t w[3] = {v[1], v[2], v[3]};
      shuffled.insert(shuffled.end(), {v[0], w[r % 3], w[(r + 1) % 3], w[(r + 2) % 3]});
    }
    auto r = tet_face_adjacency(shuffled.data(), shuffled.size() / 4, nv);
    ASSERT_TRUE(r.ok()) << r.message();
    EXPECT_EQ(r.value(), brute_force(shuffled));
    // Symmetric, and as many boundary faces as the hull has triangles.
    size_t boundary = 0;
    for (size_t i = 0; i < r.value().size(); ++i) {
      const int32_t e = r.value()[i];
      if (e == kNoTetAcross) {
        ++boundary;
        continue;
      }
      EXPECT_EQ(r.value()[size_t(e)], int32_t(i));
    }
    size_t ghosts = 0;
    for (int32_t t = 0; t < int32_t(d.value().tet_capacity()); ++t)
      ghosts += d.value().is_live(t) && d.value().is_ghost(t);
    EXPECT_EQ(boundary, ghosts);
  }
}

TEST(TetFaceAdjacency, BoundaryFaceTrianglesFindTheLastTriangleOnEachBoundaryFace) {
  auto r = tet_face_adjacency(kFan.data(), 4, 6);
  ASSERT_TRUE(r.ok());
  // Triangle 0 on t0's boundary face 1 (0,2,3), reversed; 1 an interface
  // (t0 | t1) and ignored; 2 on no face; 3 and 4 both on t3's face 1
  // (5,3,2): the last wins.
  const std::vector<int32_t> tris = {3, 2, 0, 1, 3, 0, 0, 1, 5, 5, 3, 2, 2, 3, 5};
  const auto on = boundary_face_triangles(kFan.data(), 4, r.value(), tris.data(), 5);
  std::vector<int32_t> want(16, -1);
  want[1] = 0;
  want[13] = 4;
  EXPECT_EQ(on, want);
}

}  // namespace
}  // namespace vm
