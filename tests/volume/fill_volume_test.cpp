#include "core/volume/fill_volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/mesh/enclosed_volume.h"
#include "core/quality/tet_quality.h"
// The pipeline includes the surface stage with the volume stage: their
// names must not clash (remesh_patch.h has a SizeField3D alias).
#include "core/surface/remesh_patch.h"
#include "core/volume/size_field3d.h"
#include "tests/support/tet_volume.h"
#include "tests/support/volume_inputs.h"

namespace vm {
namespace {

std::array<int32_t, 3> rotated(std::array<int32_t, 3> f) {
  while (f[0] > f[1] || f[0] > f[2]) f = {f[1], f[2], f[0]};
  return f;
}

// Faces of the tetrahedra that no other tetrahedron shares, oriented
// outward; fails on a face used more than twice or twice the same way.
std::set<std::array<int32_t, 3>> mesh_boundary(const VolumeMesh& m) {
  std::map<std::array<int32_t, 3>, std::vector<std::array<int32_t, 3>>> by_key;
  for (size_t t = 0; t < m.num_tets(); ++t)
    for (int k = 0; k < 4; ++k) {
      std::array<int32_t, 3> f;
      for (int s = 0; s < 3; ++s) f[size_t(s)] = m.tets[4 * t + size_t(kFaceOut[k][s])];
      std::array<int32_t, 3> key = f;
      std::sort(key.begin(), key.end());
      by_key[key].push_back(rotated(f));
    }
  std::set<std::array<int32_t, 3>> out;
  for (const auto& [key, fs] : by_key) {
    EXPECT_LE(fs.size(), 2u);
    if (fs.size() == 1) out.insert(fs[0]);
    if (fs.size() == 2) {
      EXPECT_NE(fs[0], fs[1]) << "two tetrahedra on the same side of a face";
    }
  }
  return out;
}

struct Outcome {
  VolumeMesh mesh;
  FillStats stats;
  QualityStats quality;
};

// Fills `in`, checks the invariants every output must satisfy, and returns
// the mesh with its quality.
Outcome fill_and_check(testing::VolumeInput& in, const FillOptions& options) {
  Outcome out;
  const std::vector<double> initial = in.kernel.points();
  const SurfaceMesh surface = in.surface;
  auto r = fill_volume(in.kernel, in.sizes, options, &out.stats);
  EXPECT_TRUE(r.ok()) << r.message();
  if (!r.ok()) return out;
  out.mesh = std::move(r.value());
  const VolumeMesh& m = out.mesh;
  EXPECT_EQ(out.stats.unused_vertices, 0u);
  EXPECT_EQ(m.tet_region, std::vector<int32_t>(m.num_tets(), 0));
  // Initial vertices first, unmoved, in their order.
  EXPECT_TRUE(std::equal(initial.begin(), initial.end(), m.points.begin()));
  // No inverted or flat tetrahedron.
  const auto q = tet_qualities(m);
  out.quality = quality_stats(q, 20);
  EXPECT_GT(out.quality.min, 0.0);
  // The boundary of the tetrahedra is exactly the surface, same
  // orientation.
  std::set<std::array<int32_t, 3>> want;
  for (size_t i = 0; i < surface.triangles.size(); i += 3)
    want.insert(
        rotated({surface.triangles[i], surface.triangles[i + 1], surface.triangles[i + 2]}));
  EXPECT_TRUE(mesh_boundary(m) == want);
  // Same volume as the enclosed one.
  double vol = 0;
  for (size_t t = 0; t < m.num_tets(); ++t) vol += testing::mesh_tet_volume6(m, t) / 6;
  const double enclosed = enclosed_volume(surface);
  EXPECT_NEAR(vol, enclosed, 1e-9 * enclosed);
  // Every vertex is used.
  std::vector<uint8_t> used(m.num_vertices(), 0);
  for (int32_t v : m.tets) used[size_t(v)] = 1;
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
  return out;
}

// Median over the edges of length / h(midpoint), h the field of the test.
double median_edge_ratio(const VolumeMesh& m, const testing::VolumeInput& in, size_t n0,
                         double gradation) {
  std::vector<double> pts, sizes;
  for (size_t v = 0; v < n0; ++v) {
    pts.insert(pts.end(), &m.points[3 * v], &m.points[3 * v] + 3);
    sizes.push_back(in.sizes[v]);
  }
  VolumeSizeOptions o;
  o.gradation = gradation;
  auto f = VolumeSizeField::build(pts, sizes, o);
  EXPECT_TRUE(f.ok());
  std::set<std::pair<int32_t, int32_t>> edges;
  for (size_t t = 0; t < m.num_tets(); ++t)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        edges.insert(std::minmax(m.tets[4 * t + size_t(i)], m.tets[4 * t + size_t(j)]));
  std::vector<double> r;
  for (auto [a, b] : edges) {
    const double* p = &m.points[3 * size_t(a)];
    const double* q = &m.points[3 * size_t(b)];
    const double mid[3] = {(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2};
    const double len = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                                 (p[2] - q[2]) * (p[2] - q[2]));
    r.push_back(len / f.value()(mid));
  }
  std::nth_element(r.begin(), r.begin() + long(r.size() / 2), r.end());
  return r[r.size() / 2];
}

// Fills the convex hull of `points` at gradations 0.25 and 0: quality at
// least 0.2 (mean 0.67), more than `min_inserted` vertices inserted, and the
// median edge within 15 % of the size field.
void check_convex_fill(const std::vector<double>& points, size_t min_inserted) {
  for (double g : {0.25, 0.0}) {
    testing::VolumeInput in;
    ASSERT_TRUE(testing::convex_input(points, &in));
    const size_t n0 = in.kernel.num_vertices();
    FillOptions o;
    o.gradation = g;
    Outcome out = fill_and_check(in, o);
    EXPECT_GE(out.quality.min, 0.2) << "g " << g;
    EXPECT_GE(out.quality.mean, 0.67) << "g " << g;
    EXPECT_GT(out.stats.inserted_vertices, min_inserted) << "g " << g;
    EXPECT_NEAR(median_edge_ratio(out.mesh, in, n0, g), 1.0, 0.15) << "g " << g;
  }
}

TEST(FillVolume, CubeQualityAndSize) { check_convex_fill(testing::cube_surface_points(10), 100); }

TEST(FillVolume, SphereQualityAndSize) { check_convex_fill(testing::sphere_points(3), 0); }

TEST(FillVolume, CappedCylinderAndCoreSize) {
  testing::VolumeInput in;
  ASSERT_TRUE(testing::convex_input(testing::capped_cylinder_points(1, 3, 0.2), &in));
  FillOptions o;
  o.core_size = 0.3;
  Outcome out = fill_and_check(in, o);
  EXPECT_GE(out.quality.min, 0.2);
  EXPECT_GE(out.quality.mean, 0.67);
  // The core size caps the edges inside: 99% below 1.5 H, none above 2 H.
  std::vector<double> lengths;
  for (size_t t = 0; t < out.mesh.num_tets(); ++t)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const double* p = &out.mesh.points[3 * size_t(out.mesh.tets[4 * t + size_t(i)])];
        const double* q = &out.mesh.points[3 * size_t(out.mesh.tets[4 * t + size_t(j)])];
        lengths.push_back(std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                                    (p[2] - q[2]) * (p[2] - q[2])));
      }
  std::sort(lengths.begin(), lengths.end());
  EXPECT_LT(lengths[lengths.size() * 99 / 100], 1.5 * 0.3);
  EXPECT_LT(lengths.back(), 2 * 0.3);
}

TEST(FillVolume, NonConvexTorus) {
  testing::VolumeInput in;
  if (!testing::torus_input(60, 24, 3, 1, &in)) GTEST_SKIP() << "torus not Delaunay-recoverable";
  // Some tetrahedra are outside (tag 0): they stay out.
  size_t outside = 0;
  in.kernel.for_each_finite_tet([&](int32_t t) { outside += in.kernel.tag(t) == 0; });
  EXPECT_GT(outside, 0u);
  Outcome out = fill_and_check(in, FillOptions{});
  EXPECT_GE(out.quality.min, 0.2);
  EXPECT_GE(out.quality.mean, 0.67);
}

TEST(FillVolume, Deterministic) {
  auto run = []() {
    testing::VolumeInput in;
    EXPECT_TRUE(testing::convex_input(testing::sphere_points(2), &in));
    auto r = fill_volume(in.kernel, in.sizes, FillOptions{}, nullptr);
    EXPECT_TRUE(r.ok());
    return r.value();
  };
  const VolumeMesh a = run(), b = run();
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.tets, b.tets);
}

TEST(FillVolume, ProgressCancelAndErrors) {
  testing::VolumeInput in;
  ASSERT_TRUE(testing::convex_input(testing::cube_surface_points(4), &in));
  double last = -1;
  bool monotone = true;
  auto r =
      fill_volume(in.kernel, in.sizes, FillOptions{}, nullptr, [&](double f, std::string_view) {
        monotone = monotone && f >= last && f <= 1;
        last = f;
        return true;
      });
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(monotone);
  EXPECT_EQ(last, 1.0);

  for (double stop_at : {0.0, 0.3, 0.7}) {
    testing::VolumeInput c;
    ASSERT_TRUE(testing::convex_input(testing::cube_surface_points(6), &c));
    auto cancelled = fill_volume(c.kernel, c.sizes, FillOptions{}, nullptr,
                                 [&](double f, std::string_view) { return f < stop_at; });
    EXPECT_FALSE(cancelled.ok());
    EXPECT_TRUE(cancelled.cancelled());
  }

  testing::VolumeInput e;
  ASSERT_TRUE(testing::convex_input(testing::cube_surface_points(3), &e));
  EXPECT_FALSE(fill_volume(e.kernel, {1.0}, FillOptions{}, nullptr).ok());
  std::vector<double> zero = e.sizes;
  zero[0] = 0;
  EXPECT_FALSE(fill_volume(e.kernel, zero, FillOptions{}, nullptr).ok());
  FillOptions wrong_tag;
  wrong_tag.region_tag = 7;
  auto empty = fill_volume(e.kernel, e.sizes, wrong_tag, nullptr);
  EXPECT_FALSE(empty.ok());
  EXPECT_NE(empty.message().find("no tetrahedron"), std::string::npos);
  FillOptions bad_field;
  bad_field.gradation = -1;
  EXPECT_FALSE(fill_volume(e.kernel, e.sizes, bad_field, nullptr).ok());
}

}  // namespace
}  // namespace vm

namespace vm {
namespace {

// Degenerate inputs: no crash, no hang, a valid mesh (or a clear error).
TEST(FillVolume, DegenerateInputs) {
  // A single tetrahedron: nothing to insert.
  {
    testing::VolumeInput in;
    ASSERT_TRUE(testing::convex_input({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}, &in));
    FillStats st;
    auto r = fill_volume(in.kernel, in.sizes, FillOptions{}, &st);
    ASSERT_TRUE(r.ok()) << r.message();
    EXPECT_EQ(r.value().num_tets(), 1u);
    EXPECT_EQ(r.value().num_vertices(), 4u);
  }
  // A thin slab (thickness 1/50 of its surface size): no room for points,
  // the tetrahedra stay flat but valid.
  {
    std::vector<double> pts;
    for (int i = 0; i <= 10; ++i)
      for (int j = 0; j <= 10; ++j)
        for (double z : {0.0, 0.002}) pts.insert(pts.end(), {0.1 * i, 0.1 * j, z});
    testing::VolumeInput in;
    ASSERT_TRUE(testing::convex_input(pts, &in));
    auto r = fill_volume(in.kernel, in.sizes, FillOptions{}, nullptr);
    ASSERT_TRUE(r.ok()) << r.message();
    const auto q = tet_qualities(r.value());
    EXPECT_GT(*std::min_element(q.begin(), q.end()), 0.0f);
  }
  // A size far larger than the domain: nothing inserted; far smaller with
  // a cap on the points: stops at the cap.
  {
    testing::VolumeInput in;
    ASSERT_TRUE(testing::convex_input(testing::cube_surface_points(3), &in));
    std::vector<double> big(in.sizes.size(), 100.0);
    FillStats st;
    ASSERT_TRUE(fill_volume(in.kernel, big, FillOptions{}, &st).ok());
    EXPECT_EQ(st.inserted_vertices, 0u);
  }
  {
    testing::VolumeInput in;
    ASSERT_TRUE(testing::convex_input(testing::cube_surface_points(3), &in));
    std::vector<double> tiny(in.sizes.size(), 1e-3);
    FillOptions o;
    o.refine.max_points = 500;
    FillStats st;
    auto r = fill_volume(in.kernel, tiny, o, &st);
    ASSERT_TRUE(r.ok()) << r.message();
    EXPECT_TRUE(st.refine.hit_max_points);
    EXPECT_LE(st.refine.inserted, 500 + 64);
    const auto q = tet_qualities(r.value());
    EXPECT_GT(*std::min_element(q.begin(), q.end()), 0.0f);
  }
  // Non-finite size.
  {
    testing::VolumeInput in;
    ASSERT_TRUE(testing::convex_input(testing::cube_surface_points(3), &in));
    std::vector<double> bad = in.sizes;
    bad[3] = NAN;
    EXPECT_FALSE(fill_volume(in.kernel, bad, FillOptions{}, nullptr).ok());
  }
}

}  // namespace
}  // namespace vm
