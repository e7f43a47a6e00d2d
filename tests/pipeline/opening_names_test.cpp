#include "core/pipeline/opening_names.h"

#include <gtest/gtest.h>

#include "core/pipeline/option_table.h"

namespace vm {
namespace {

/// A prepared surface with n openings, the file naming some of them.
PreparedSurface with_openings(size_t n, std::vector<std::string> file_names = {}) {
  PreparedSurface s;
  s.topology.openings.resize(n);
  s.opening_sources.resize(n);
  for (size_t i = 0; i < file_names.size() && i < n; ++i) s.opening_sources[i].name = file_names[i];
  return s;
}

TEST(OpeningNames, DefaultsFollowTheAnalysisOrder) {
  auto names = opening_names(with_openings(4), {}, 0);
  ASSERT_TRUE(names.ok());
  EXPECT_EQ(names.value(), (std::vector<std::string>{"inlet", "outlet_1", "outlet_2", "outlet_3"}));
  // Another inlet: the outlets keep the table's order around it.
  names = opening_names(with_openings(4), {}, 2);
  EXPECT_EQ(names.value(), (std::vector<std::string>{"outlet_1", "outlet_2", "inlet", "outlet_3"}));
}

TEST(OpeningNames, UserNamesWinThenTheFilesThenDefaults) {
  auto names = opening_names(with_openings(3, {"aorta", "", "wall"}), {{1, "renal"}}, 0);
  ASSERT_TRUE(names.ok()) << names.message();
  // "wall" in the file is reserved: the default takes its place.
  EXPECT_EQ(names.value(), (std::vector<std::string>{"aorta", "renal", "outlet_1"}));
  names = opening_names(with_openings(2, {"aorta", "aorta"}), {}, 0);
  ASSERT_TRUE(names.ok());
  EXPECT_EQ(names.value(), (std::vector<std::string>{"aorta", "outlet_1"}));
}

TEST(OpeningNames, RefusalsNameTheOption) {
  auto out_of_range = opening_names(with_openings(3), {{3, "x"}}, 0);
  ASSERT_FALSE(out_of_range.ok());
  EXPECT_EQ(phrase_error(out_of_range.status(), kFaceCli),
            "--name names opening 4, but there are 3 openings");
  auto reserved = opening_names(with_openings(3), {{0, "lumen"}}, 0);
  EXPECT_EQ(reserved.status().option(), "name");
  auto prefixed = opening_names(with_openings(3), {{0, "wall_in"}}, 0);
  EXPECT_FALSE(prefixed.ok());
  auto twice = opening_names(with_openings(3), {{0, "a"}, {2, "a"}}, 0);
  ASSERT_FALSE(twice.ok());
  EXPECT_EQ(phrase_error(twice.status(), kFaceCli),
            "--name gives 'a' to openings 1 and 3: each name once");
  // A user name equal to a default another opening takes.
  auto clash = opening_names(with_openings(3), {{2, "outlet_1"}}, 0);
  EXPECT_FALSE(clash.ok());
  auto inlet = opening_names(with_openings(0), {}, 1);
  EXPECT_EQ(phrase_error(inlet.status(), kFaceJs),
            "inlet cannot be used: the surface has no opening");
}

TEST(OpeningNames, ValidNames) {
  for (const char* good : {"a", "inlet", "LCA_2", "x-y",
                           "A234567890123456789012345678901234567890123456789012345678901234"})
    EXPECT_TRUE(valid_group_name(good)) << good;
  for (const char* bad : {"", "1a", "_a", "a b", "a/b", "é",
                          "A2345678901234567890123456789012345678901234567890123456789012345"})
    EXPECT_FALSE(valid_group_name(bad)) << bad;
}

}  // namespace
}  // namespace vm
