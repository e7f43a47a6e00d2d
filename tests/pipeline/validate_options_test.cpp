#include "core/pipeline/validate_options.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "core/pipeline/option_table.h"
#include "core/pipeline/solver_preset.h"

namespace vm {
namespace {

/// The option a refusal names, "" when accepted.
std::string refused(const MeshJobOptions& o, std::optional<OutputFormat> f = std::nullopt) {
  Status st = validate_options(o, f);
  if (st.ok()) return "";
  EXPECT_EQ(st.kind(), ErrorKind::kBadOption) << st.message();
  return std::string(st.option());
}

TEST(ValidateOptions, TheDefaultsPass) { EXPECT_EQ(refused(MeshJobOptions{}), ""); }

TEST(ValidateOptions, SizesAreCheckedAsAWhole) {
  MeshJobOptions o;
  o.remesh_options.size.mode = SizeMode::kUniform;
  o.remesh_options.size.size = 0;  // a uniform size never given a value
  EXPECT_EQ(refused(o), "size");
  o = {};
  o.remesh_options.size.per_circumference = 2;
  EXPECT_EQ(refused(o), "per_circumference");
  o = {};
  o.remesh_options.size.size_min = 2;
  o.remesh_options.size.size_max = 1;
  EXPECT_EQ(refused(o), "size_min");
  o = {};
  o.remesh_options.size.spheres.push_back({{0, 0, 0}, 1, std::numeric_limits<double>::infinity()});
  EXPECT_EQ(refused(o), "refine");
}

TEST(ValidateOptions, AFirstLayerFromYPlusNeedsItsFlowAndLayers) {
  MeshJobOptions o;
  o.yplus.yplus = 1;
  EXPECT_EQ(refused(o), "first_layer_yplus");  // no inlet velocity
  o.yplus.velocity = 0.3;
  EXPECT_EQ(refused(o), "");
  o.viscous.first_height = 0.01;
  EXPECT_EQ(refused(o), "first_layer_yplus");  // two first heights
  o.viscous.first_height = 0;
  o.viscous.layers = 0;
  EXPECT_EQ(refused(o), "first_layer_yplus");  // nothing to size
}

TEST(ValidateOptions, ASurfaceOnlyJobMakesNoVolume) {
  MeshJobOptions o;
  o.volume = false;
  EXPECT_EQ(refused(o, OutputFormat::kVtu), "format");
  EXPECT_EQ(refused(o, OutputFormat::kMsh), "");
  o.family = 3;
  EXPECT_EQ(refused(o, OutputFormat::kMsh), "family");
}

TEST(ValidateOptions, BinaryMshIsVersion41Only) {
  MeshJobOptions o;
  o.msh_binary = true;
  EXPECT_EQ(refused(o), "");
  o.msh_version = MshVersion::k22;
  EXPECT_EQ(refused(o), "msh_binary");
  EXPECT_EQ(refused(o, OutputFormat::kMsh), "msh_binary");
  EXPECT_EQ(refused(o, OutputFormat::kVtu), "");  // no MSH file is written
}

// The CLI and JS path (apply_options) refuses before the job starts, in
// the interface's words.
TEST(ValidateOptions, ApplyingOptionsValidates) {
  const OptionSpec* yplus = find_option("first_layer_yplus");
  ASSERT_NE(yplus, nullptr);
  OptionValue v;
  v.number = 1;
  std::pair<const OptionSpec*, OptionValue> given[] = {{yplus, v}};
  MeshJobOptions o;
  Status st = apply_options(o, given);
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(phrase_error(st, kFaceCli),
            "--first-layer-yplus needs the flow's --inlet-velocity (m/s) to size the first layer");
}

}  // namespace
}  // namespace vm
