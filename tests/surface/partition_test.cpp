#include "core/surface/partition.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/mesh/adjacency.h"
#include "core/mesh/boundary_loops.h"
#include "core/mesh/topology.h"
#include "core/param/lscm.h"
#include "core/phantom/vessel_phantom.h"
#include "core/util/parallel.h"
#include "tests/param/param_test_meshes.h"
#include "tests/support/phantoms.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

const PatchMapFn kLscm = [](const SurfaceMesh& patch) { return lscm(patch); };

using testing::phantom;

// Checks every documented property of a partition of `in`.
void check_partition(const SurfaceMesh& in, const std::vector<MappedPatch>& patches,
                     const PartitionOptions& o, const std::string& name) {
  SCOPED_TRACE(name);
  // Every input triangle in exactly one patch.
  std::vector<int> uses(in.num_triangles(), 0);
  for (const MappedPatch& p : patches)
    for (int32_t t : p.triangle_of) {
      EXPECT_GE(t, 0);
      EXPECT_LT(size_t(t), in.num_triangles());
      if (t >= 0 && size_t(t) < in.num_triangles()) ++uses[size_t(t)];
    }
  size_t missing = 0, repeated = 0;
  for (int u : uses) missing += u == 0, repeated += u > 1;
  EXPECT_EQ(missing, 0u) << "input triangles in no patch";
  EXPECT_EQ(repeated, 0u) << "input triangles in several patches";

  for (size_t i = 0; i < patches.size(); ++i) {
    const MappedPatch& p = patches[i];
    SCOPED_TRACE("patch " + std::to_string(i) + " of " + std::to_string(patches.size()) + ", " +
                 std::to_string(p.mesh.num_triangles()) + " triangles");
    ASSERT_GT(p.mesh.num_triangles(), 0u);
    ASSERT_EQ(p.triangle_of.size(), p.mesh.num_triangles());
    ASSERT_EQ(p.vertex_of.size(), p.mesh.num_vertices());
    EXPECT_LE(p.mesh.num_triangles(), o.max_patch_triangles);
    // The local copy is the input: same points, same triangles, same
    // orientation.
    for (size_t v = 0; v < p.vertex_of.size(); ++v)
      for (int k = 0; k < 3; ++k)
        ASSERT_EQ(p.mesh.points[3 * v + k], in.points[3 * size_t(p.vertex_of[v]) + k]);
    for (size_t t = 0; t < p.mesh.num_triangles(); ++t)
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(p.vertex_of[size_t(p.mesh.triangles[3 * t + c])],
                  in.triangles[3 * size_t(p.triangle_of[t]) + c]);
    // A topological disk: V - E + F = 1, one boundary loop that holds every
    // boundary edge (no pinched vertex), connected, manifold.
    const TriangleAdjacency adj = build_adjacency(p.mesh);
    EXPECT_EQ(adj.num_nonmanifold_edges, 0u);
    const long chi =
        long(p.mesh.num_vertices()) - long(adj.num_edges) + long(p.mesh.num_triangles());
    EXPECT_EQ(chi, 1);
    const auto loops = boundary_loops(p.mesh, adj);
    EXPECT_EQ(loops.size(), 1u);
    size_t boundary_half_edges = 0, loop_vertices = 0;
    for (int32_t o2 : adj.opposite) boundary_half_edges += o2 == TriangleAdjacency::kBoundary;
    for (const auto& l : loops) loop_vertices += l.size();
    EXPECT_EQ(loop_vertices, boundary_half_edges);
    const TopologyReport topo = analyze_topology(p.mesh, adj);
    EXPECT_EQ(topo.components, 1);
    EXPECT_EQ(topo.nonmanifold_vertices, 0u);
    EXPECT_EQ(topo.genus, 0);
    // The map: one finite uv per vertex, nothing folded, not crowded
    // (unless marked unmappable, for the fallback).
    if (!p.unmappable.empty()) continue;
    ASSERT_EQ(p.map.uv.size(), 2 * p.mesh.num_vertices());
    for (double x : p.map.uv) ASSERT_TRUE(std::isfinite(x));
    EXPECT_EQ(count_flipped(p.mesh, p.map.uv), 0u);
    EXPECT_EQ(p.map.flipped_triangles, 0u);
    const double ratio = conformal_factor_ratio(p.mesh, p.map.uv);
    EXPECT_NEAR(p.factor_ratio, ratio, 1e-9 * ratio);
    if (p.mesh.num_triangles() >= 8) {
      EXPECT_LE(ratio, o.max_factor_ratio);
    }
  }
}

// Partitions `m` for LSCM maps with options `o`, checks the result
// (check_partition) and returns it; a failure fails the test (and gives no
// patches).
std::vector<MappedPatch> checked_partition(const SurfaceMesh& m, const std::string& name,
                                           PartitionStats* stats = nullptr,
                                           const PartitionOptions& o = {}) {
  auto r = partition_for_maps(m, build_adjacency(m), kLscm, o, stats);
  EXPECT_TRUE(r.ok()) << r.message();
  if (!r.ok()) return {};
  check_partition(m, r.value(), o, name);
  return r.value();
}

void print_partition(const std::string& name, const SurfaceMesh& m,
                     const std::vector<MappedPatch>& patches, const PartitionStats& stats) {
  std::cout << "[ info ] " << name << ": " << m.num_triangles() << " triangles -> "
            << patches.size() << " patches, " << stats.bisections << " bisections, "
            << stats.rejected_maps << " rejected maps\n";
}

TEST(Partition, OpenTubeIsSplitIntoDisks) {
  // Two openings: an annulus, not a disk, so it must be cut.
  const SurfaceMesh tube = testing::open_tube(24, 16, 1.0, 4.0);
  PartitionStats stats;
  EXPECT_GE(checked_partition(tube, "open tube", &stats).size(), 2u);
  EXPECT_GE(stats.bisections, 1u);
}

TEST(Partition, ClosedPhantomWithoutBoundary) {
  const SurfaceMesh m = phantom(PhantomKind::kTube, /*open_ends=*/false, 0.15);
  ASSERT_GT(m.num_triangles(), 0u);
  const TopologyReport topo = analyze_topology(m);
  ASSERT_TRUE(topo.closed);
  ASSERT_EQ(topo.genus, 0);
  // A closed surface is not a disk (and LSCM needs a boundary): cut.
  PartitionStats stats;
  const auto patches = checked_partition(m, "closed tube phantom", &stats);
  EXPECT_GE(patches.size(), 2u);
  EXPECT_GE(stats.bisections, 1u);
  print_partition("closed tube", m, patches, stats);
}

TEST(Partition, TorusPhantomOfGenusOne) {
  const SurfaceMesh m = phantom(PhantomKind::kTorus, true, 0.15);
  ASSERT_GT(m.num_triangles(), 0u);
  const TopologyReport topo = analyze_topology(m);
  ASSERT_EQ(topo.genus, 1);
  ASSERT_TRUE(topo.closed);
  PartitionStats stats;
  const auto patches = checked_partition(m, "torus phantom", &stats);
  EXPECT_GE(patches.size(), 2u);
  print_partition("torus", m, patches, stats);
}

TEST(Partition, NoisyBifurcationPhantom) {
  const SurfaceMesh m = phantom(PhantomKind::kBifurcation, true, 0.15, 0.3);
  ASSERT_GT(m.num_triangles(), 0u);
  EXPECT_GE(checked_partition(m, "noisy bifurcation").size(), 3u);
}

TEST(Partition, TighterLimitsGiveMoreSmallerPatches) {
  const SurfaceMesh m = phantom(PhantomKind::kTube, true, 0.15);
  ASSERT_GT(m.num_triangles(), 0u);
  const TriangleAdjacency adj = build_adjacency(m);
  PartitionOptions loose;
  auto a = partition_for_maps(m, adj, kLscm, loose);
  ASSERT_TRUE(a.ok()) << a.message();
  check_partition(m, a.value(), loose, "default limits");

  // A tight crowding limit refuses maps the default accepts: the same
  // bisections continue further.
  PartitionOptions tight;
  tight.max_factor_ratio = 1.1;
  PartitionStats tight_stats;
  auto b = partition_for_maps(m, adj, kLscm, tight, &tight_stats);
  ASSERT_TRUE(b.ok()) << b.message();
  check_partition(m, b.value(), tight, "factor ratio 1.1");
  EXPECT_GT(tight_stats.rejected_maps, 0u);
  EXPECT_GE(b.value().size(), a.value().size());

  PartitionOptions small;
  small.max_patch_triangles = m.num_triangles() / 10;
  auto c = partition_for_maps(m, adj, kLscm, small);
  ASSERT_TRUE(c.ok()) << c.message();
  check_partition(m, c.value(), small, "max 1/10 of the triangles");
  EXPECT_GE(c.value().size(), 10u);
  std::cout << "[ info ] tube phantom: " << a.value().size() << " patches (default), "
            << b.value().size() << " (factor ratio 1.1), " << c.value().size() << " (max "
            << small.max_patch_triangles << " triangles)\n";
}

TEST(Partition, AFlatDiskIsOnePatch) {
  const SurfaceMesh m = testing::disk(8, 6, 0.3, [](double x, double y) {
    return std::array<double, 3>{x, y, 0.0};
  });
  PartitionStats stats;
  const auto patches = checked_partition(m, "flat disk", &stats);
  ASSERT_EQ(patches.size(), 1u);
  EXPECT_EQ(stats.bisections, 0u);
  EXPECT_EQ(stats.rejected_maps, 0u);
  // LSCM of a planar patch is a similarity: no crowding at all.
  EXPECT_NEAR(patches[0].factor_ratio, 1.0, 1e-6);
}

TEST(Partition, ErrorsAreReported) {
  const SurfaceMesh tube = testing::open_tube(16, 8);
  const TriangleAdjacency adj = build_adjacency(tube);
  // The tube needs at least one bisection: depth 0 is not enough.
  PartitionOptions shallow;
  shallow.max_depth = 0;
  EXPECT_FALSE(partition_for_maps(tube, adj, kLscm, shallow).ok());
  // A failing map is split further, down to pieces too small to split,
  // which are patches marked unmappable (for the fallback), not silent.
  PatchMapFn failing = [](const SurfaceMesh&) -> Result<Parametrization> {
    return Result<Parametrization>::Error("no map today");
  };
  PartitionStats stats;
  auto r = partition_for_maps(tube, adj, failing, {}, &stats);
  ASSERT_TRUE(r.ok()) << r.message();
  check_partition(tube, r.value(), {}, "no map");
  EXPECT_GT(stats.rejected_maps, 0u);
  for (const MappedPatch& p : r.value()) {
    EXPECT_LT(p.triangle_of.size(), 8u);
    EXPECT_NE(p.unmappable.find("no map today"), std::string::npos) << p.unmappable;
  }
  // At the depth limit a disk whose map still fails is marked too.
  const SurfaceMesh square = testing::square_grid(6);
  auto d = partition_for_maps(square, build_adjacency(square), failing, shallow);
  ASSERT_TRUE(d.ok()) << d.message();
  ASSERT_EQ(d.value().size(), 1u);
  EXPECT_NE(d.value()[0].unmappable.find("after 0 bisections"), std::string::npos)
      << d.value()[0].unmappable;
}

TEST(Partition, SamePatchesOnAnyThreadCount) {
  // Pieces of one depth run on the threads; the patches (and their order)
  // and the error reported must not depend on how many.
  const SurfaceMesh m = phantom(PhantomKind::kBifurcation, true, 0.15, 0.3);
  const TriangleAdjacency adj = build_adjacency(m);
  PartitionOptions o;
  o.max_patch_triangles = m.num_triangles() / 40;
  // Fails on the patches whose centroid has x > 0.3, naming the centroid.
  PatchMapFn failing = [](const SurfaceMesh& patch) -> Result<Parametrization> {
    double c[3] = {0, 0, 0};
    for (size_t i = 0; i < patch.points.size(); ++i) c[i % 3] += patch.points[i];
    for (double& x : c) x /= double(patch.num_vertices());
    if (c[0] > 0.3)
      return Result<Parametrization>::Error("no map at " + std::to_string(c[0]) + " " +
                                            std::to_string(c[1]) + " " + std::to_string(c[2]));
    return lscm(patch);
  };
  std::vector<std::vector<int32_t>> first;
  PartitionStats first_stats;
  std::string first_error;
  for (int threads : {1, 2, 3}) {
    SCOPED_TRACE(threads);
    set_thread_count(threads);
    PartitionStats stats;
    auto r = partition_for_maps(m, adj, kLscm, o, &stats);
    ASSERT_TRUE(r.ok()) << r.message();
    std::vector<std::vector<int32_t>> tris;
    for (const MappedPatch& p : r.value()) tris.push_back(p.triangle_of);
    // The failing maps: split down to unmappable pieces, the same ones.
    auto e = partition_for_maps(m, adj, failing, o);
    ASSERT_TRUE(e.ok()) << e.message();
    std::string unmappable;
    for (const MappedPatch& p : e.value()) unmappable += p.unmappable + ";";
    EXPECT_NE(unmappable.find("no map at"), std::string::npos);
    if (threads == 1) {
      check_partition(m, r.value(), o, "1 thread");
      EXPECT_GE(tris.size(), 40u);
      first = tris, first_stats = stats, first_error = unmappable;
      continue;
    }
    EXPECT_EQ(tris, first);
    EXPECT_EQ(stats.bisections, first_stats.bisections);
    EXPECT_EQ(stats.rejected_maps, first_stats.rejected_maps);
    EXPECT_EQ(unmappable, first_error);
  }
  set_thread_count(0);
}

TEST(ConformalFactor, SimilarityHasRatioOne) {
  // A disk in a tilted plane (an isometric embedding of the planar disk).
  const double ct = std::cos(1.0), st = std::sin(1.0);
  const SurfaceMesh m = testing::disk(6, 6, 0.3, [&](double x, double y) {
    return std::array<double, 3>{x, ct * y, st * y};
  });
  // uv = 2.5 * a rotation of the in-plane coordinates (x, y).
  std::vector<double> uv(2 * m.num_vertices());
  const double c = std::cos(0.4), s = std::sin(0.4);
  for (size_t v = 0; v < m.num_vertices(); ++v) {
    const double x = m.points[3 * v], y = m.points[3 * v + 1] / ct;
    uv[2 * v] = 2.5 * (c * x - s * y);
    uv[2 * v + 1] = 2.5 * (s * x + c * y);
  }
  const std::vector<double> f = conformal_factors(m, uv);
  ASSERT_EQ(f.size(), m.num_triangles());
  for (double x : f) EXPECT_NEAR(x, 2.5, 1e-9);
  EXPECT_NEAR(conformal_factor_ratio(m, uv), 1.0, 1e-9);
  // Pulling a ring vertex across the center folds its triangles: their
  // factor is 0.
  std::vector<double> folded = uv;
  const size_t v1 = 1;  // first vertex of the first ring
  folded[2 * v1] *= -3;
  folded[2 * v1 + 1] *= -3;
  const size_t flipped = count_flipped(m, folded);
  EXPECT_GT(flipped, 0u);
  size_t zero = 0;
  for (double x : conformal_factors(m, folded)) zero += x == 0;
  EXPECT_EQ(zero, flipped);
}

}  // namespace
}  // namespace vm
