#include "core/volume/tet_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "core/mesh/volume_mesh.h"
#include "tests/support/tet_volume.h"
#include "tests/support/volume_inputs.h"

namespace vm {
namespace {

// The octahedron around the edge (0, 1) as 4 tetrahedra, every vertex fixed.
TetMesh octahedron() { return testing::octahedron_tets(1); }

TEST(TetMesh, FromArraysAdjacencyAndRing) {
  TetMesh m = octahedron();
  ASSERT_TRUE(m.check().ok()) << m.check().message();
  EXPECT_EQ(m.num_tets(), 4u);
  int boundary = 0;
  for (int32_t t = 0; t < 4; ++t)
    for (int k = 0; k < 4; ++k) boundary += m.neighbor(t, k) == TetMesh::kBoundary;
  EXPECT_EQ(boundary, 8);
  std::vector<int32_t> ring_tets, ring;
  ASSERT_TRUE(m.edge_ring(0, 0, 1, ring_tets, ring));
  EXPECT_EQ(ring.size(), 4u);
  // Boundary edges cannot be removed.
  const int32_t* v = m.tet(0);
  int32_t other = -1;
  for (int s = 0; s < 4; ++s)
    if (v[s] != 0 && v[s] != 1) other = v[s];
  EXPECT_FALSE(m.edge_ring(0, 0, other, ring_tets, ring));
  std::vector<int32_t> star;
  m.star(0, star);
  EXPECT_EQ(star.size(), 4u);
}

TEST(TetMesh, EdgeRingOrderAndSizeLimit) {
  // Every removable edge of a Delaunay mesh of the cube with interior
  // points: ring_tets[i] is (a, b, ring[i], ring[i + 1]), positive in that
  // order, from whichever tetrahedron of the ring the walk starts.
  testing::VolumeInput in;
  ASSERT_TRUE(testing::convex_input(testing::cube_surface_points(3), &in));
  const double inner[4][3] = {{0.3, 0.4, 0.5}, {0.6, 0.55, 0.45}, {0.5, 0.3, 0.7}, {0.4, 0.7, 0.3}};
  for (const auto& p : inner) in.kernel.insert(p, -1, true);
  const size_t n = in.kernel.num_vertices();
  std::vector<int32_t> vmap(n);
  for (size_t v = 0; v < n; ++v) vmap[v] = int32_t(v);
  auto r = TetMesh::from_kernel(in.kernel, 1, vmap, int32_t(n), std::vector<uint8_t>(n, 0));
  ASSERT_TRUE(r.ok()) << r.message();
  const TetMesh& m = r.value();
  ASSERT_TRUE(m.check().ok()) << m.check().message();
  std::vector<int32_t> ring_tets, ring, again_tets, again;
  int removable = 0;
  for (int32_t t = 0; t < int32_t(m.capacity()); ++t) {
    if (!m.is_live(t)) continue;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) {
        const int32_t a = m.tet(t)[i], b = m.tet(t)[j];
        if (!m.edge_ring(t, a, b, ring_tets, ring)) continue;
        ++removable;
        const size_t k = ring.size();
        ASSERT_GE(k, 3u);
        ASSERT_EQ(ring_tets.size(), k);
        EXPECT_EQ(ring_tets[0], t);
        for (size_t q = 0; q < k; ++q) {
          const int32_t* v = m.tet(ring_tets[q]);
          for (int32_t x : {a, b, ring[q], ring[(q + 1) % k]})
            EXPECT_NE(std::find(v, v + 4, x), v + 4);
          EXPECT_GT(
              tet_volume6(m.point(a), m.point(b), m.point(ring[q]), m.point(ring[(q + 1) % k])), 0);
        }
        // The size limit: refused below the ring's size, accepted at it.
        EXPECT_FALSE(m.edge_ring(t, a, b, again_tets, again, int(k) - 1));
        ASSERT_TRUE(m.edge_ring(t, a, b, again_tets, again, int(k)));
        EXPECT_EQ(again, ring);
      }
  }
  EXPECT_GT(removable, 0);
}

TEST(TetMesh, ReplaceKeepsBoundaryAndRejectsMismatch) {
  TetMesh m = octahedron();
  const double vol = testing::total_volume(m);
  std::vector<int32_t> ring_tets, ring;
  ASSERT_TRUE(m.edge_ring(0, 0, 1, ring_tets, ring));
  // The 4-4 flip: diagonal ring[0]-ring[2].
  std::vector<std::array<int32_t, 4>> nt;
  for (int i = 1; i <= 2; ++i) {
    const int32_t x = ring[0], y = ring[size_t(i)], z = ring[size_t(i + 1) % 4];
    nt.push_back({x, y, z, 1});
    nt.push_back({y, x, z, 0});
  }
  // A wrong set (one tetrahedron missing) is refused, nothing changes.
  EXPECT_FALSE(m.replace(ring_tets.data(), 4, nt.data(), 3, nullptr));
  ASSERT_TRUE(m.check().ok());
  std::vector<int32_t> ids;
  ASSERT_TRUE(m.replace(ring_tets.data(), 4, nt.data(), 4, &ids));
  ASSERT_TRUE(m.check().ok()) << m.check().message();
  EXPECT_EQ(ids.size(), 4u);
  EXPECT_NEAR(testing::total_volume(m), vol, 1e-12);
  int boundary = 0;
  for (int32_t t : ids)
    for (int k = 0; k < 4; ++k) boundary += m.neighbor(t, k) == TetMesh::kBoundary;
  EXPECT_EQ(boundary, 8);
}

TEST(TetMesh, FromKernelKeepsRegionAndConstraints) {
  testing::VolumeInput in;
  ASSERT_TRUE(testing::convex_input(testing::cube_surface_points(3), &in));
  const Delaunay3D& d = in.kernel;
  std::vector<int32_t> vmap(d.num_vertices());
  for (size_t v = 0; v < vmap.size(); ++v) vmap[v] = int32_t(v);
  auto r =
      TetMesh::from_kernel(d, 1, vmap, int32_t(vmap.size()), std::vector<uint8_t>(vmap.size(), 1));
  ASSERT_TRUE(r.ok()) << r.message();
  const TetMesh& m = r.value();
  ASSERT_TRUE(m.check().ok()) << m.check().message();
  EXPECT_EQ(m.num_tets(), d.num_finite_tets());
  size_t boundary = 0;
  for (int32_t t = 0; t < int32_t(m.capacity()); ++t)
    for (int k = 0; k < 4; ++k) boundary += m.neighbor(t, k) == TetMesh::kBoundary;
  EXPECT_EQ(boundary, in.surface.num_triangles());
  EXPECT_NEAR(testing::total_volume(m), 1.0, 1e-12);
  // Errors: wrong sizes.
  EXPECT_FALSE(TetMesh::from_kernel(d, 1, {}, 0, {}).ok());
  EXPECT_FALSE(TetMesh::from_arrays({0, 0, 0}, {0, 0, 0, 1}, {0}).ok());
}

}  // namespace
}  // namespace vm
