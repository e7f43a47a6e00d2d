#include "core/mesh/prism_split.h"

#include <gtest/gtest.h>

namespace vm {
namespace {

TEST(PrismSplit, QuadsAreCutFromTheirSmallestIdLikeThePrismsFaces) {
  const int32_t q1[4] = {5, 2, 7, 9}, q2[4] = {4, 8, 1, 6};
  const auto a = split_quad(q1), b = split_quad(q2);
  // From 2 (position 1): triangles (2, 7, 9) and (2, 9, 5), same cycle order.
  EXPECT_EQ(a[0], (std::array<int32_t, 3>{2, 7, 9}));
  EXPECT_EQ(a[1], (std::array<int32_t, 3>{2, 9, 5}));
  EXPECT_EQ(b[0], (std::array<int32_t, 3>{4, 8, 1}));
  EXPECT_EQ(b[1], (std::array<int32_t, 3>{4, 1, 6}));
  // The prism with these ids cuts its side face (ids 1, 2, 5, 4 of a prism
  // 0..5 relabelled) the same way: the diagonal from the smallest id.
  const int32_t prism[6] = {10, 2, 7, 11, 9, 5};
  const int32_t side[4] = {2, 7, 5, 9};  // the face 1-2-5-4 of the prism
  const auto cut = split_quad(side);
  bool found = false;
  for (const auto& tet : split_prism(prism)) {
    int shared = 0;
    for (int32_t v : tet)
      for (int32_t w : cut[0]) shared += v == w;
    found = found || shared == 3;
  }
  EXPECT_TRUE(found);
}

}  // namespace
}  // namespace vm
