#include "core/surface/fidelity.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/mesh/adjacency.h"
#include "core/mesh/self_intersection.h"
#include "core/mesh/surface_distance.h"
#include "core/mesh/topology.h"
#include "core/quality/triangle_quality.h"
#include "core/surface/optimize_surface.h"
#include "tests/support/phantoms.h"
#include "tests/support/remesh_options.h"

namespace vm {
namespace {

/// A phantom remeshed at a uniform size with every fidelity round off, and
/// the per-vertex data the rounds start from.
struct Unpinned {
  SurfaceMesh input;
  RemeshOptions options;
  RemeshedSurface out;
  WallVertices wall;
  std::vector<double> asked;  ///< the uniform size h, per input vertex
};

constexpr double kH = 0.3;

Unpinned unpinned_bifurcation(double h) {
  Unpinned u;
  u.input = testing::phantom(PhantomKind::kBifurcation, true, 0.1, 0.1);
  u.options = testing::uniform_remesh(h);
  u.options.feature_angle_degrees = 180;  // no creases: the plain adjacency
  u.options.fidelity_rounds = u.options.fidelity_size_rounds = 0;
  auto r = remesh_surface(u.input, u.options);
  EXPECT_TRUE(r.ok()) << r.message();
  if (!r.ok()) return u;
  u.out = std::move(r).value();
  u.asked.assign(u.input.num_vertices(), h);
  u.wall.home = u.out.home;
  u.wall.size = u.out.sizes;
  u.wall.fixed.resize(u.out.home.size());
  for (size_t v = 0; v < u.wall.fixed.size(); ++v)
    u.wall.fixed[v] = u.out.on_opening[v] ? kOnOpening : kFree;
  u.options.fidelity_rounds = RemeshOptions{}.fidelity_rounds;
  return u;
}

size_t count_far(const std::vector<double>& gaps, double limit) {
  return size_t(std::count_if(gaps.begin(), gaps.end(), [&](double g) { return g > limit; }));
}

TEST(Fidelity, PinningRoundsBringFarInputVerticesOntoTheWall) {
  const double h = kH;
  Unpinned u = unpinned_bifurcation(h);
  ASSERT_GT(u.out.mesh.num_triangles(), 0u);
  const SurfaceMesh& in = u.input;
  const size_t far_before = count_far(distances_to_surface(u.out.mesh, in.points, true).per_point,
                                      u.options.fidelity * h);
  ASSERT_GT(far_before, 0u) << "the phantom should have far input vertices";
  const QualityStats q0 = quality_stats(triangle_qualities(u.out.mesh));
  const size_t openings = analyze_topology(u.out.mesh).openings.size();

  SurfaceMesh mesh = u.out.mesh;
  std::vector<double> gaps;
  RemeshStats stats;
  std::vector<double> sizes = u.asked;
  pin_far_input_vertices(in, build_adjacency(in), sizes, u.asked, u.options, mesh, u.wall, gaps,
                         stats);

  // The gaps returned are the wall's, and far fewer are beyond the limit.
  const std::vector<double> real = distances_to_surface(mesh, in.points, true).per_point;
  ASSERT_EQ(gaps.size(), real.size());
  for (size_t v = 0; v < gaps.size(); ++v) EXPECT_NEAR(gaps[v], real[v], 1e-12);
  const size_t far_after = count_far(gaps, u.options.fidelity * h);
  std::cout << "[ info ] far input vertices " << far_before << " -> " << far_after << " ("
            << stats.fidelity_pinned << " pinned in " << stats.fidelity_rounds << " rounds)\n";
  EXPECT_GT(stats.fidelity_rounds, 0u);
  EXPECT_GT(stats.fidelity_pinned, 0u);
  EXPECT_LT(far_after, far_before / 2);

  // The per-vertex arrays stay parallel to the mesh; every pinned vertex
  // lies within its slack of the input vertex it is pinned to.
  const size_t nv = mesh.num_vertices();
  ASSERT_EQ(u.wall.home.size(), nv);
  ASSERT_EQ(u.wall.fixed.size(), nv);
  ASSERT_EQ(u.wall.pin_of.size(), nv);
  ASSERT_EQ(u.wall.size.size(), nv);
  size_t pinned = 0;
  for (size_t v = 0; v < nv; ++v) {
    if (u.wall.fixed[v] != kPinned) continue;
    ++pinned;
    const int32_t p = u.wall.pin_of[v];
    ASSERT_TRUE(p >= 0 && size_t(p) < in.num_vertices());
    const double* a = &mesh.points[3 * v];
    const double* b = &in.points[3 * size_t(p)];
    EXPECT_LE(std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]),
              u.options.fidelity_pin_slack * u.options.fidelity * h + 1e-12);
  }
  EXPECT_EQ(pinned, stats.fidelity_pinned);

  // Still on the input, same openings, no self-intersection, floors held.
  EXPECT_LE(distances_to_surface(in, mesh.points).max, 1e-9);
  EXPECT_EQ(analyze_topology(mesh).openings.size(), openings);
  EXPECT_EQ(find_self_intersections(mesh, 0).pairs, 0u);
  EXPECT_EQ(stats.self_intersections, 0);
  const QualityStats q1 = quality_stats(triangle_qualities(mesh));
  EXPECT_GE(q1.min, std::min(q0.min, u.options.fidelity_floor_min));
  EXPECT_GE(q1.mean, std::min(q0.mean, u.options.fidelity_floor_mean));
}

TEST(Fidelity, SizeRoundsMakeTheSizeFinerAtFarVerticesAndKeepTheBestWall) {
  const double h = kH;
  Unpinned u = unpinned_bifurcation(h);
  ASSERT_GT(u.out.mesh.num_triangles(), 0u);
  const SurfaceMesh& in = u.input;
  const std::vector<double> first_gaps = u.out.input_gaps;
  const double limit = u.options.fidelity * h;
  ASSERT_GT(count_far(first_gaps, limit), 0u);
  u.options.fidelity_size_rounds = 3;
  // A remesher that hands back the first wall with no gap left: one round,
  // then nothing is far.
  std::vector<std::vector<double>> asked_sizes;
  Result<RemeshedSurface> result(u.out);
  RemeshStats stats;
  const Status status = refine_size_where_far(
      in, u.options, u.asked, u.asked, result, stats,
      [&](const std::vector<double>& sizes, RemeshStats&) -> Result<RemeshedSurface> {
        asked_sizes.push_back(sizes);
        RemeshedSurface closer = u.out;
        std::fill(closer.input_gaps.begin(), closer.input_gaps.end(), 0.0);
        return closer;
      });
  ASSERT_TRUE(status.ok()) << status.message();
  ASSERT_EQ(asked_sizes.size(), 1u);
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(count_far(result.value().input_gaps, limit), 0u);
  EXPECT_EQ(stats.fidelity_size_rounds, 1u);
  // Finer (by 0.5 to 0.9) at every far vertex, never coarser, never below
  // the smallest size allowed.
  const std::vector<double>& finer = asked_sizes[0];
  ASSERT_EQ(finer.size(), in.num_vertices());
  for (size_t v = 0; v < finer.size(); ++v) {
    EXPECT_LE(finer[v], h);
    EXPECT_GE(finer[v], std::max(0.5 * h, u.options.size.size_min));
    if (first_gaps[v] > limit) {
      EXPECT_LE(finer[v], 0.9 * h + 1e-12);
    }
  }

  // A cancelled remeshing is returned as such.
  Result<RemeshedSurface> again(u.out);
  const Status cancelled = refine_size_where_far(
      in, u.options, u.asked, u.asked, again, stats,
      [](const std::vector<double>&, RemeshStats&) -> Result<RemeshedSurface> {
        return Status::Cancelled();
      });
  EXPECT_TRUE(cancelled.cancelled());
}

TEST(Fidelity, LocalSizeRoundsHalveTheSizeAroundWhatThePinsLeaveFar) {
  const double h = kH;
  Unpinned u = unpinned_bifurcation(h);
  ASSERT_GT(u.out.mesh.num_triangles(), 0u);
  const SurfaceMesh& in = u.input;
  const TriangleAdjacency adj = build_adjacency(in);
  // The same rounds without and with local size rounds (the pinning rounds
  // are deterministic: both walls are the same until the first local one).
  struct Run {
    SurfaceMesh mesh;
    WallVertices wall;
    std::vector<double> sizes, gaps;
    RemeshStats stats;
  };
  auto run = [&](int local_rounds) {
    Run r{u.out.mesh, u.wall, u.asked, {}, {}};
    RemeshOptions o = u.options;
    o.fidelity_local_rounds = local_rounds;
    pin_far_input_vertices(in, adj, r.sizes, u.asked, o, r.mesh, r.wall, r.gaps, r.stats);
    return r;
  };
  const Run off = run(0), on = run(2);
  const double limit = u.options.fidelity * h;
  const size_t far_off = count_far(off.gaps, limit), far_on = count_far(on.gaps, limit);
  std::cout << "[ info ] far after the pinning rounds " << far_off << ", after "
            << on.stats.fidelity_local_rounds << " local size rounds " << far_on << "\n";
  ASSERT_GT(far_off, 0u) << "the pinning rounds should leave some far here";
  EXPECT_EQ(off.stats.fidelity_local_rounds, 0u);
  EXPECT_EQ(off.sizes, u.asked);
  EXPECT_GT(on.stats.fidelity_local_rounds, 0u);
  EXPECT_LT(far_on, far_off);
  // Finer (at most by half) only near what was far, never coarser.
  size_t finer = 0;
  for (size_t v = 0; v < on.sizes.size(); ++v) {
    EXPECT_LE(on.sizes[v], h);
    EXPECT_GE(on.sizes[v], 0.5 * h * (1 - 1e-12));
    finer += on.sizes[v] < h;
  }
  EXPECT_GT(finer, 0u);
  EXPECT_LT(finer, on.sizes.size() / 4);
  // The wall: its data in step, on the input, no crossing, floors held,
  // the gaps its own.
  ASSERT_EQ(on.wall.size.size(), on.mesh.num_vertices());
  ASSERT_EQ(on.wall.home.size(), on.mesh.num_vertices());
  EXPECT_LE(distances_to_surface(in, on.mesh.points).max, 1e-9);
  EXPECT_EQ(find_self_intersections(on.mesh, 0).pairs, 0u);
  const QualityStats q0 = quality_stats(triangle_qualities(u.out.mesh));
  const QualityStats q1 = quality_stats(triangle_qualities(on.mesh));
  EXPECT_GE(q1.min, std::min(q0.min, u.options.fidelity_floor_min));
  EXPECT_GE(q1.mean, std::min(q0.mean, u.options.fidelity_floor_mean));
  EXPECT_EQ(on.gaps, distances_to_surface(on.mesh, in.points, true).per_point);
}

TEST(Fidelity, ASizeRoundIsWorthItForSomeFarVerticesButNotForNoise) {
  RemeshOptions o;
  o.fidelity_small_surface = 1000;
  o.fidelity_size_share = 0.01;
  o.fidelity_noise_share = 0.2;
  EXPECT_FALSE(worth_size_round(0, 500, o));
  EXPECT_TRUE(worth_size_round(1, 500, o));     // a small wall: any far vertex
  EXPECT_TRUE(worth_size_round(100, 500, o));   // a share of 0.2 is not noise yet
  EXPECT_FALSE(worth_size_round(101, 500, o));  // beyond it, noise everywhere
  EXPECT_FALSE(worth_size_round(10, 2000, o));  // a large wall: a share of 0.005
  EXPECT_TRUE(worth_size_round(21, 2000, o));   // above its share of 0.01
}

}  // namespace
}  // namespace vm
