#include "core/mesh/face_groups.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <numeric>
#include <random>
#include <vector>

namespace vm {
namespace {

constexpr int32_t T = kNoFourthVertex;

/// The groups as lists of face indices, in group order.
std::vector<std::vector<uint32_t>> groups_of(const FaceGroups& g) {
  std::vector<std::vector<uint32_t>> out;
  for (size_t k = 0; k < g.num_groups(); ++k) {
    out.emplace_back();
    for (size_t i = 0; i < g.size(k); ++i) out.back().push_back(g.face(k, i));
  }
  return out;
}

/// The sorted vertex list of face i, a triangle's 4th as -1 in front of
/// nothing: compared lexicographically as the groups are ordered.
std::vector<int32_t> sorted_key(const std::vector<int32_t>& faces, size_t i) {
  std::vector<int32_t> k(faces.begin() + long(4 * i), faces.begin() + long(4 * i + 4));
  if (k[3] == kNoFourthVertex) k.pop_back();
  std::sort(k.begin(), k.end());
  return k;
}

/// Brute force: the faces stable-sorted by sorted vertex list (a list
/// before its extensions), cut where the list changes.
std::vector<std::vector<uint32_t>> brute_force(const std::vector<int32_t>& faces) {
  const size_t n = faces.size() / 4;
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return sorted_key(faces, a) < sorted_key(faces, b);
  });
  std::vector<std::vector<uint32_t>> out;
  for (size_t i = 0; i < n; ++i) {
    if (i == 0 || sorted_key(faces, order[i]) != sorted_key(faces, order[i - 1]))
      out.emplace_back();
    out.back().push_back(order[i]);
  }
  return out;
}

/// The offsets are well formed: from 0 to num_faces, no empty group, and
/// order a permutation of the faces.
void expect_well_formed(const FaceGroups& g, size_t num_faces) {
  ASSERT_FALSE(g.group_start.empty());
  EXPECT_EQ(g.group_start.front(), 0u);
  EXPECT_EQ(g.group_start.back(), num_faces);
  for (size_t k = 0; k < g.num_groups(); ++k) EXPECT_LT(g.group_start[k], g.group_start[k + 1]);
  std::vector<uint32_t> sorted = g.order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<uint32_t> all(num_faces);
  std::iota(all.begin(), all.end(), 0u);
  EXPECT_EQ(sorted, all);
}

TEST(FaceGroups, EmptyInputHasNoGroups) {
  for (size_t nv : {size_t(0), size_t(5)}) {
    const FaceGroups g = group_faces(nullptr, 0, nv);
    EXPECT_EQ(g.num_groups(), 0u);
    EXPECT_TRUE(g.order.empty());
    EXPECT_EQ(g.group_start, std::vector<uint32_t>{0});
  }
}

TEST(FaceGroups, MixedTrianglesAndQuadsGroupByVertexSetInKeyOrder) {
  // Orientation and starting vertex do not matter; a quad's set differs
  // from each triangle's.
  const std::vector<int32_t> faces = {
      5, 6, 7, 8,  // 0: quad {5,6,7,8}
      2, 1, 0, T,  // 1: triangle {0,1,2}
      8, 7, 6, 5,  // 2: the quad 0 reversed
      3, 4, 1, T,  // 3: triangle {1,3,4}
      0, 2, 1, T,  // 4: triangle 1 reversed
      7, 8, 5, 6,  // 5: quad 0 rotated
      4, 1, 3, T,  // 6: triangle 3 rotated
      1, 4, 5, 0,  // 7: quad {0,1,4,5}, alone
  };
  const FaceGroups g = group_faces(faces.data(), 8, 9);
  expect_well_formed(g, 8);
  // {0,1,2} < {0,1,4,5} < {1,3,4} < {5,6,7,8}.
  const std::vector<std::vector<uint32_t>> want = {{1, 4}, {7}, {3, 6}, {0, 2, 5}};
  EXPECT_EQ(groups_of(g), want);
  EXPECT_EQ(groups_of(g), brute_force(faces));
}

TEST(FaceGroups, TriangleOnThreeVerticesOfAQuadIsAnotherFaceAndComesFirst) {
  // The quad listed first; the triangle on its three smallest vertices
  // still comes first (a triangle sorts as if its 4th vertex were -1), the
  // triangle on its three largest after both.
  const std::vector<int32_t> faces = {3, 2, 1, 0, 1, 2, 3, T, 2, 1, 0, T, 0, 1, 2, 3};
  const FaceGroups g = group_faces(faces.data(), 4, 4);
  expect_well_formed(g, 4);
  const std::vector<std::vector<uint32_t>> want = {{2}, {0, 3}, {1}};
  EXPECT_EQ(groups_of(g), want);
}

TEST(FaceGroups, FacesInsideAGroupStayInInputOrder) {
  // Ten copies of one triangle in rotations and reflections, interleaved
  // with copies of another: each group lists its faces by index.
  std::vector<int32_t> faces;
  std::vector<uint32_t> first, second;
  const std::array<std::array<int32_t, 3>, 6> turns = {
      {{4, 2, 9}, {2, 9, 4}, {9, 4, 2}, {9, 2, 4}, {2, 4, 9}, {4, 9, 2}}};
  for (uint32_t i = 0; i < 20; ++i) {
    const auto& t = turns[(i * 7) % 6];
    if (i % 3 == 1) {
      faces.insert(faces.end(), {t[0], t[1], 3, T});  // {2,3,4}, {2,3,9} or {3,4,9}
    } else {
      faces.insert(faces.end(), {t[0], t[1], t[2], T});
      first.push_back(i);
    }
  }
  const FaceGroups g = group_faces(faces.data(), 20, 10);
  expect_well_formed(g, 20);
  EXPECT_EQ(groups_of(g), brute_force(faces));
  bool found = false;
  for (const auto& group : groups_of(g)) {
    EXPECT_TRUE(std::is_sorted(group.begin(), group.end()));
    if (group.front() == first.front()) {
      EXPECT_EQ(group, first);
      found = true;
    }
  }
  EXPECT_TRUE(found);
}

TEST(FaceGroups, ThreeFacesOnOneSetFormOneGroup) {
  // Face (0, 1, 2) of three tetrahedra around it, and a quad on three
  // prisms' sides: groups of 3, among groups of 1.
  const std::vector<int32_t> faces = {0, 1, 2, T, 2, 1, 0, T, 1, 2, 6, T, 0, 2,
                                      1, T, 6, 7, 9, 8, 8, 9, 7, 6, 9, 8, 6, 7};
  const FaceGroups g = group_faces(faces.data(), 7, 10);
  expect_well_formed(g, 7);
  const std::vector<std::vector<uint32_t>> want = {{0, 1, 3}, {2}, {4, 5, 6}};
  EXPECT_EQ(groups_of(g), want);
}

TEST(FaceGroups, RandomMixedFacesMatchBruteForce) {
  // Few vertices, so that many faces coincide, in buckets large enough for
  // the bucket sort's other branch.
  for (uint32_t seed : {1u, 2u, 3u, 4u}) {
    std::mt19937 rng(seed);
    const int32_t nv = seed < 3 ? 6 : 40;
    std::vector<int32_t> faces;
    const size_t n = 400;
    for (size_t i = 0; i < n; ++i) {
      std::vector<int32_t> v(static_cast<size_t>(nv));
      std::iota(v.begin(), v.end(), 0);
      std::shuffle(v.begin(), v.end(), rng);
      const bool quad = rng() % 2 == 0;
      faces.insert(faces.end(), {v[0], v[1], v[2], quad ? v[3] : T});
    }
    const FaceGroups g = group_faces(faces.data(), n, size_t(nv));
    expect_well_formed(g, n);
    EXPECT_EQ(groups_of(g), brute_force(faces));
    // Faces of a group have one vertex list; consecutive groups differ.
    for (size_t k = 0; k < g.num_groups(); ++k) {
      for (size_t i = 1; i < g.size(k); ++i) {
        EXPECT_EQ(sorted_key(faces, g.face(k, i)), sorted_key(faces, g.face(k, 0)));
      }
      if (k > 0) {
        EXPECT_LT(sorted_key(faces, g.face(k - 1, 0)), sorted_key(faces, g.face(k, 0)));
      }
    }
  }
}

}  // namespace
}  // namespace vm
