#include "core/volume/optimize_volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/quality/tet_quality.h"
#include "core/util/parallel.h"
#include "tests/support/tet_volume.h"
#include "tests/support/volume_inputs.h"

namespace vm {
namespace {

// The Delaunay tetrahedralization of the cube's surface grid plus random
// interior points (many slivers), as a TetMesh with the surface fixed.
TetMesh random_cube_mesh(int grid, int interior, uint32_t seed, std::vector<double>* h) {
  testing::VolumeInput in;
  EXPECT_TRUE(testing::convex_input(testing::cube_surface_points(grid), &in));
  const size_t n0 = in.kernel.num_vertices();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  for (int i = 0; i < interior; ++i) {
    const double p[3] = {u(rng), u(rng), u(rng)};
    in.kernel.insert(p, -1, true);
  }
  const size_t n = in.kernel.num_vertices();
  std::vector<int32_t> vmap(n);
  std::vector<uint8_t> fixed(n);
  for (size_t v = 0; v < n; ++v) vmap[v] = int32_t(v), fixed[v] = v < n0;
  auto r = TetMesh::from_kernel(in.kernel, 1, vmap, int32_t(n), fixed);
  EXPECT_TRUE(r.ok()) << r.message();
  h->assign(n, 1.0 / grid);
  return std::move(r.value());
}

std::set<std::array<int32_t, 3>> boundary_faces(const TetMesh& m) {
  std::set<std::array<int32_t, 3>> out;
  for (int32_t t = 0; t < int32_t(m.capacity()); ++t) {
    if (!m.is_live(t)) continue;
    for (int k = 0; k < 4; ++k)
      if (m.neighbor(t, k) == TetMesh::kBoundary)
        out.insert({m.tet(t)[kFaceOut[k][0]], m.tet(t)[kFaceOut[k][1]], m.tet(t)[kFaceOut[k][2]]});
  }
  // Rotate each to start at its smallest index (same oriented triangle).
  std::set<std::array<int32_t, 3>> norm;
  for (auto f : out) {
    while (f[0] > f[1] || f[0] > f[2]) f = {f[1], f[2], f[0]};
    norm.insert(f);
  }
  return norm;
}

TEST(OptimizeVolume, RemovesSliversOfARandomDelaunayMesh) {
  std::vector<double> h;
  TetMesh m = random_cube_mesh(6, 400, 7, &h);
  const auto faces = boundary_faces(m);
  const std::vector<double> before_points = m.points();
  const std::vector<int32_t> before_tets = m.tets();
  const size_t n0 = m.num_vertices();
  OptimizeStats st;
  ASSERT_TRUE(optimize_volume(m, h, OptimizeOptions{}, &st).ok());
  ASSERT_TRUE(m.check().ok()) << m.check().message();
  EXPECT_LT(st.before.min, 0.05);
  EXPECT_GT(st.after.min, st.before.min);
  EXPECT_GE(st.after.min, 0.2);
  EXPECT_GT(st.after.mean, st.before.mean + 0.05);
  EXPECT_GT(st.edge_removals + st.flips23, 0);
  EXPECT_GT(st.smoothing_moves, 0);
  // Fixed vertices did not move; the boundary is the same set of faces;
  // the volume is unchanged.
  for (size_t v = 0; v < n0; ++v) {
    if (!m.is_fixed(int32_t(v))) continue;
    for (int c = 0; c < 3; ++c) EXPECT_EQ(m.point(int32_t(v))[c], before_points[3 * v + c]);
  }
  EXPECT_EQ(boundary_faces(m), faces);
  EXPECT_NEAR(testing::total_volume(m), 1.0, 1e-12);
  // The summaries (from the optimizer's cached qualities) match the meshes.
  const auto q = tet_qualities(m.points(), m.tets());
  EXPECT_FLOAT_EQ(float(st.after.min), *std::min_element(q.begin(), q.end()));
  EXPECT_EQ(st.after.count, m.num_tets());
  EXPECT_NEAR(st.after.mean, quality_stats(q, 20).mean, 1e-6);
  const auto q0 = tet_qualities(before_points, before_tets);
  EXPECT_EQ(st.before.count, q0.size());
  EXPECT_FLOAT_EQ(float(st.before.min), *std::min_element(q0.begin(), q0.end()));
  EXPECT_NEAR(st.before.mean, quality_stats(q0, 20).mean, 1e-6);
}

TEST(OptimizeVolume, DeterministicCancellableAndErrors) {
  std::vector<double> h;
  TetMesh a = random_cube_mesh(4, 100, 3, &h);
  TetMesh b = random_cube_mesh(4, 100, 3, &h);
  ASSERT_TRUE(optimize_volume(a, h, OptimizeOptions{}, nullptr).ok());
  ASSERT_TRUE(optimize_volume(b, h, OptimizeOptions{}, nullptr).ok());
  EXPECT_EQ(a.points(), b.points());
  EXPECT_EQ(a.tets(), b.tets());

  TetMesh c = random_cube_mesh(4, 100, 3, &h);
  Status s = optimize_volume(c, h, OptimizeOptions{}, nullptr,
                             [](double, std::string_view) { return false; });
  EXPECT_TRUE(s.cancelled());
  EXPECT_TRUE(c.check().ok());
  EXPECT_FALSE(optimize_volume(c, std::vector<double>(2, 1.0), OptimizeOptions{}, nullptr).ok());
}

TEST(OptimizeVolume, SlabsGiveTheSameMeshOnAnyThreadCount) {
  // The first flip pass (6,000 tetrahedra below the threshold here) and the
  // smoothing pass work on the slabs at the same time on 2 and 3 threads,
  // one slab after the other on 1: the same mesh, valid and improved.
  struct Outcome {
    std::vector<double> points;
    std::vector<int32_t> tets;
    OptimizeStats st;
  };
  auto run = [](int threads) {
    set_thread_count(threads);
    std::vector<double> h;
    TetMesh m = random_cube_mesh(10, 3000, 11, &h);
    Outcome out;
    EXPECT_TRUE(optimize_volume(m, h, OptimizeOptions{}, &out.st).ok());
    EXPECT_TRUE(m.check().ok()) << m.check().message();
    out.points = m.points();
    out.tets = m.tets();
    set_thread_count(0);
    return out;
  };
  const Outcome one = run(1), two = run(2), three = run(3);
  EXPECT_GT(one.st.smoothing_moves, 1000);
  EXPECT_GE(one.st.after.min, 0.2);
  EXPECT_GT(one.st.after.mean, one.st.before.mean + 0.05);
  EXPECT_EQ(one.points, two.points);
  EXPECT_EQ(one.tets, two.tets);
  EXPECT_EQ(one.points, three.points);
  EXPECT_EQ(one.tets, three.tets);
  EXPECT_EQ(one.st.smoothing_moves, two.st.smoothing_moves);
}

}  // namespace
}  // namespace vm
