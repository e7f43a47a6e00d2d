#include "core/prepare/units.h"

#include <gtest/gtest.h>

namespace vm {
namespace {

TEST(Units, GivenUnitsAreKept) {
  for (LengthUnit u : {LengthUnit::kMm, LengthUnit::kCm, LengthUnit::kM}) {
    const ModelUnit m = decide_unit(u, 0.001);
    EXPECT_EQ(m.unit, u);
    EXPECT_FALSE(m.guessed);
    EXPECT_EQ(parse_unit(unit_symbol(u)), u);
  }
  EXPECT_EQ(parse_unit("inch"), LengthUnit::kGuess);
  EXPECT_DOUBLE_EQ(metres_per_unit(LengthUnit::kCm) / metres_per_unit(LengthUnit::kMm), 10);
}

TEST(Units, SmallRadiiAreMetresLargerOnesUnconfirmedMillimetres) {
  const ModelUnit carotid_in_m = decide_unit(LengthUnit::kGuess, 0.003);
  EXPECT_EQ(carotid_in_m.unit, LengthUnit::kM);
  EXPECT_TRUE(carotid_in_m.guessed);
  EXPECT_TRUE(carotid_in_m.certain);
  EXPECT_NE(carotid_in_m.reason.find("0.003"), std::string::npos);
  for (double r : {0.08, 0.5, 2.0, 12.0}) {  // cm or mm: cannot be told apart
    const ModelUnit u = decide_unit(LengthUnit::kGuess, r);
    EXPECT_EQ(u.unit, LengthUnit::kMm) << r;
    EXPECT_FALSE(u.certain) << r;
  }
}

}  // namespace
}  // namespace vm
