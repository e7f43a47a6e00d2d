// The preparation gives the same surface and report with any thread count
// (core/util/parallel.h): inputs of several chunks of the parallel loops.
#include <gtest/gtest.h>

#include <vector>

#include "core/io/stl.h"
#include "core/phantom/vessel_phantom.h"
#include "core/pipeline/prepare_surface.h"
#include "core/pipeline/report_json.h"
#include "core/util/parallel.h"
#include "tests/support/phantoms.h"

namespace vm {
namespace {

PreparedSurface prepared_with(const std::vector<uint8_t>& bytes, int threads) {
  set_thread_count(threads);
  auto r = prepare_surface(bytes);
  set_thread_count(0);
  EXPECT_TRUE(r.ok()) << r.message();
  return r.ok() ? r.value() : PreparedSurface{};
}

void expect_same_with_1_and_2_threads(const PhantomOptions& o) {
  const std::vector<uint8_t> bytes = write_stl_binary(testing::phantom(o));
  ASSERT_GT(bytes.size() / 50, size_t(3) << 16) << "fewer triangles than 3 chunks";
  const PreparedSurface one = prepared_with(bytes, 1), two = prepared_with(bytes, 2);
  ASSERT_GT(one.mesh.num_triangles(), 0u);
  EXPECT_EQ(one.mesh.points, two.mesh.points);
  EXPECT_EQ(one.mesh.triangles, two.mesh.triangles);
  EXPECT_EQ(one.warnings, two.warnings);
  EXPECT_EQ(one.quality, two.quality);
  EXPECT_EQ(analysis_json(one), analysis_json(two));
}

TEST(PrepareThreads, ARawStaircaseIsTheSame) {
  PhantomOptions o;
  o.kind = PhantomKind::kBifurcation;
  o.voxel = 0.032;
  o.binary = true;
  expect_same_with_1_and_2_threads(o);
}

TEST(PrepareThreads, ADirtyCappedTubeIsTheSame) {
  PhantomOptions o;
  o.kind = PhantomKind::kTube;
  o.voxel = 0.03;
  o.noise = 0.3;
  o.flat_caps = true;
  o.dirty = true;
  expect_same_with_1_and_2_threads(o);
}

}  // namespace
}  // namespace vm
