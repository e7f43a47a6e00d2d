#include "core/surface/pin_to_input.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "core/mesh/self_intersection.h"
#include "core/mesh/surface_distance.h"
#include "core/mesh/topology.h"
#include "core/quality/triangle_quality.h"
#include "core/surface/optimize_surface.h"
#include "core/surface/remesh_surface.h"
#include "tests/support/phantoms.h"
#include "tests/support/remesh_options.h"
#include "tests/support/test_meshes.h"

namespace vm {
namespace {

// Every directed edge once, every edge at most twice: a consistently
// oriented manifold.
bool oriented_manifold(const SurfaceMesh& m) {
  std::map<std::pair<int32_t, int32_t>, int> directed;
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k)
      if (directed[{m.triangles[3 * t + k], m.triangles[3 * t + (k + 1) % 3]}]++ > 0) return false;
  return true;
}

// The z component of each triangle's normal is positive: nothing folded.
bool faces_up(const SurfaceMesh& m) {
  for (size_t t = 0; t < m.num_triangles(); ++t) {
    const double* a = &m.points[3 * size_t(m.triangles[3 * t])];
    const double* b = &m.points[3 * size_t(m.triangles[3 * t + 1])];
    const double* c = &m.points[3 * size_t(m.triangles[3 * t + 2])];
    if (!((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0)) return false;
  }
  return true;
}

// A fine grid with one spike, remeshed as a coarse flat grid whose vertices
// lie on the fine one.
struct SpikeCase {
  SurfaceMesh input = testing::square_grid(20), output = testing::square_grid(4);
  int32_t spike = 8 * 21 + 7;  // input vertex (7, 8): (0.35, 0.4)
  WallVertices wall;
  std::vector<double> h;
  explicit SpikeCase(double height = 0.05) {
    input.points[3 * size_t(spike) + 2] = height;
    wall.home.assign(output.num_vertices(), 0);
    wall.fixed.assign(output.num_vertices(), kFree);
    wall.pin_of.assign(output.num_vertices(), -1);
    h.assign(input.num_vertices(), 0.25);
  }
  std::vector<double> gaps() const {
    return distances_to_surface(output, input.points, true).per_point;
  }
};

TEST(PinToInput, AnOutputVertexLandsOnTheFarInputVertex) {
  SpikeCase c;
  const std::vector<double> before = c.gaps();
  ASSERT_NEAR(before[size_t(c.spike)], 0.05, 1e-12);  // 0.2 h
  const size_t nt = c.output.num_triangles();
  const PinStats st = pin_to_input(c.output, c.wall, c.input, c.h, before, 0.1, {});
  // Only the spike and its 1-ring (under 0.1 h = 0.025 only the spike) are far.
  EXPECT_EQ(st.far, 1u);
  EXPECT_EQ(st.pinned, 1u);
  const std::vector<double> after = c.gaps();
  EXPECT_EQ(after[size_t(c.spike)], 0.0);
  for (size_t v = 0; v < after.size(); ++v) EXPECT_LE(after[v], 0.1 * 0.25 + 1e-12) << v;
  size_t pinned = 0;
  for (size_t v = 0; v < c.wall.fixed.size(); ++v) {
    if (c.wall.fixed[v] != kPinned) continue;
    ++pinned;
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(c.output.points[3 * v + size_t(k)],
                c.input.points[3 * size_t(c.spike) + size_t(k)]);
    const int32_t* T = &c.input.triangles[3 * size_t(c.wall.home[v])];
    EXPECT_TRUE(T[0] == c.spike || T[1] == c.spike || T[2] == c.spike);
  }
  EXPECT_EQ(pinned, 1u);
  EXPECT_TRUE(oriented_manifold(c.output));
  EXPECT_TRUE(faces_up(c.output));
  EXPECT_GE(c.output.num_triangles(), nt);
  EXPECT_EQ(c.wall.home.size(), c.output.num_vertices());
  // Every output vertex still lies on the input.
  EXPECT_LE(distances_to_surface(c.input, c.output.points).max, 1e-12);
}

TEST(PinToInput, SkippedVerticesAndNearOnesAreLeftAlone) {
  SpikeCase c;
  std::vector<uint8_t> skip(c.input.num_vertices(), 0);
  skip[size_t(c.spike)] = 1;
  const SurfaceMesh original = c.output;
  EXPECT_EQ(pin_to_input(c.output, c.wall, c.input, c.h, c.gaps(), 0.1, skip).pinned, 0u);
  // A looser limit than the spike's gap: nothing to do either.
  EXPECT_EQ(pin_to_input(c.output, c.wall, c.input, c.h, c.gaps(), 0.5, {}).far, 0u);
  EXPECT_EQ(c.output.points, original.points);
  EXPECT_EQ(c.output.triangles, original.triangles);
}

TEST(PinToInput, UnpinPoorFreesPinsInPoorTrianglesAndRemembersThem) {
  SpikeCase c;
  ASSERT_EQ(pin_to_input(c.output, c.wall, c.input, c.h, c.gaps(), 0.1, {}).pinned, 1u);
  std::vector<uint8_t> skip(c.input.num_vertices(), 0);
  double worst = 1;
  for (size_t t = 0; t < c.output.num_triangles(); ++t) {
    const int32_t* T = &c.output.triangles[3 * t];
    worst = std::min(worst, triangle_gamma(&c.output.points[3 * size_t(T[0])],
                                           &c.output.points[3 * size_t(T[1])],
                                           &c.output.points[3 * size_t(T[2])]));
  }
  // Below the worst triangle: nothing freed.
  EXPECT_EQ(unpin_poor(c.output, c.wall, worst * 0.99, skip), 0u);
  EXPECT_EQ(std::count(skip.begin(), skip.end(), 1), 0);
  // Above every triangle: the pin is freed and its input vertex skipped.
  EXPECT_EQ(unpin_poor(c.output, c.wall, 1.01, skip), 1u);
  EXPECT_EQ(std::count(c.wall.fixed.begin(), c.wall.fixed.end(), kPinned), 0);
  EXPECT_EQ(skip[size_t(c.spike)], 1);
  EXPECT_EQ(std::count(skip.begin(), skip.end(), 1), 1);
}

TEST(PinToInput, PinnedVerticesSlideOnlyWithinTheSlack) {
  // The same pinned surface optimized three ways: pins held (slack 0),
  // sliding within 0.08 h, and a slack of 0.08 h never given (no PinSlack).
  auto optimized = [](double slack, bool with_pin_of) {
    SpikeCase c(0.03);  // 0.12 h
    EXPECT_EQ(pin_to_input(c.output, c.wall, c.input, c.h, c.gaps(), 0.1, {}).pinned, 1u);
    const TriangleAdjacency adj = build_adjacency(c.input);
    const TriangleBvh bvh = build_triangle_bvh(c.input);
    for (size_t v = 0; v < c.output.num_vertices(); ++v)  // home: the input triangle under v
      if (c.wall.fixed[v] != kPinned)
        c.wall.home[v] = closest_surface_point(c.input, bvh, &c.output.points[3 * v]).triangle;
    for (size_t v = 0; v < c.output.num_vertices(); ++v)  // the boundary stays
      if (c.output.points[3 * v] == 0 || c.output.points[3 * v] == 1 ||
          c.output.points[3 * v + 1] == 0 || c.output.points[3 * v + 1] == 1)
        c.wall.fixed[v] = kOnOpening;
    c.wall.size.assign(c.output.num_vertices(), 0.25);
    PinSlack pins;
    pins.input_h = &c.h;
    pins.slack = slack;
    optimize_on_surface(c.output, c.wall, c.input, adj, {}, {}, with_pin_of ? &pins : nullptr);
    if (with_pin_of) {
      EXPECT_EQ(c.wall.pin_of.size(), c.output.num_vertices());
    }
    return c;
  };
  const SpikeCase held = optimized(0, true), slid = optimized(0.08, true),
                  no_pin_of = optimized(0.08, false);
  // The pinned vertex's distance to its input vertex (-1: none).
  auto pinned_offset = [](const SpikeCase& c) {
    double offset = -1;
    for (size_t v = 0; v < c.wall.fixed.size(); ++v)
      if (c.wall.fixed[v] == kPinned) {
        EXPECT_EQ(c.wall.pin_of[v], c.spike);
        const double* x = &c.output.points[3 * v];
        const double* s = &c.input.points[3 * size_t(c.spike)];
        offset = std::hypot(x[0] - s[0], x[1] - s[1], x[2] - s[2]);
      }
    return offset;
  };
  EXPECT_EQ(pinned_offset(held), 0.0);
  EXPECT_EQ(pinned_offset(no_pin_of), 0.0);
  const double moved = pinned_offset(slid);
  EXPECT_GT(moved, 0.0) << "the slack should let the pinned vertex improve its triangles";
  EXPECT_LE(moved, 0.08 * 0.25 * (1 + 1e-9));
  // Still within 0.1 h of the spike, and at least as good a worst triangle.
  EXPECT_LE(
      distances_to_surface(slid.output, slid.input.points, true).per_point[size_t(slid.spike)],
      0.08 * 0.25 * (1 + 1e-9));
  EXPECT_GE(quality_stats(triangle_qualities(slid.output)).min,
            quality_stats(triangle_qualities(held.output)).min - 1e-12);
  EXPECT_LE(distances_to_surface(slid.input, slid.output.points).max, 1e-12);
}

TEST(RemeshSurface, FidelityRoundsBringTheInputCloserWithoutLosingQuality) {
  const SurfaceMesh in = testing::phantom(PhantomKind::kBifurcation, true, 0.1, 0.1);
  RemeshOptions o = testing::uniform_remesh(0.3);
  RemeshStats off_stats, on_stats;
  o.fidelity_rounds = o.fidelity_size_rounds = 0;
  auto off = remesh_surface(in, o, &off_stats);
  o.fidelity_rounds = RemeshOptions{}.fidelity_rounds;
  auto on = remesh_surface(in, o, &on_stats);
  ASSERT_TRUE(off.ok()) << off.message();
  ASSERT_TRUE(on.ok()) << on.message();
  // The reported gaps are the real ones.
  for (const auto* r : {&off.value(), &on.value()}) {
    const std::vector<double> gaps = distances_to_surface(r->mesh, in.points, true).per_point;
    ASSERT_EQ(gaps.size(), r->input_gaps.size());
    for (size_t v = 0; v < gaps.size(); ++v) EXPECT_NEAR(gaps[v], r->input_gaps[v], 1e-12);
  }
  ASSERT_GT(off_stats.input_gap_vertices, 0u) << "the phantom should have far input vertices";
  const QualityStats q0 = quality_stats(triangle_qualities(off.value().mesh));
  const QualityStats q1 = quality_stats(triangle_qualities(on.value().mesh));
  std::cout << "[ info ] far input vertices " << off_stats.input_gap_vertices << " -> "
            << on_stats.input_gap_vertices << " (" << on_stats.fidelity_pinned
            << " pinned), max gap " << off_stats.max_input_gap << " -> " << on_stats.max_input_gap
            << " h; gamma min " << q0.min << " -> " << q1.min << ", mean " << q0.mean << " -> "
            << q1.mean << (on_stats.fidelity_reverted ? " (reverted)" : "") << " rounds "
            << on_stats.fidelity_rounds << "\n";
  // A round may be undone (with the wall's vertices along a Hilbert curve
  // the first one left two needles here); the kept rounds still pin.
  EXPECT_GT(on_stats.fidelity_pinned, 0u);
  EXPECT_LT(on_stats.input_gap_vertices, off_stats.input_gap_vertices / 2);
  EXPECT_GE(q1.min, std::min(q0.min, o.fidelity_floor_min));
  EXPECT_GE(q1.mean, std::min(q0.mean, o.fidelity_floor_mean));
  // Still on the input, and not crossing itself.
  EXPECT_LE(distances_to_surface(in, on.value().mesh.points).max, 1e-9);
  EXPECT_EQ(find_self_intersections(on.value().mesh, 0).pairs, 0u);
  // The pinning rounds counted the pairs (exactly: there were none before
  // them); without rounds nothing was counted.
  EXPECT_EQ(on_stats.self_intersections, 0);
  EXPECT_EQ(off_stats.self_intersections, -1);
}

}  // namespace
}  // namespace vm

namespace vm {
namespace {

TEST(RemeshSurface, PinningIsUndoneWhenTheQualityFloorsCannotHold) {
  // Noise everywhere, pinned all the same (no share limit): the quality
  // drops below what it was, and the floors at 1 leave no room for that.
  const SurfaceMesh in = testing::phantom(PhantomKind::kBifurcation, true, 0.15, 0.3);
  RemeshOptions o = testing::uniform_remesh(0.2);
  o.fidelity_max_share = 1;
  o.fidelity_floor_min = 1;
  o.fidelity_size_rounds = 0;
  o.fidelity_rounds = 0;
  // Pins held exactly and no relaxing: nothing can make up for them.
  o.fidelity_pin_slack = 0;
  o.fidelity_passes = 0;
  RemeshStats off_stats, undone_stats;
  auto off = remesh_surface(in, o, &off_stats);
  o.fidelity_rounds = 3;
  o.fidelity_floor_mean = 1;
  auto undone = remesh_surface(in, o, &undone_stats);
  ASSERT_TRUE(off.ok()) << off.message();
  ASSERT_TRUE(undone.ok()) << undone.message();
  EXPECT_GT(undone_stats.fidelity_rounds, 0u);
  EXPECT_TRUE(undone_stats.fidelity_reverted);
  EXPECT_EQ(undone_stats.fidelity_pinned, 0u);
  // The surface before pinning, and its own gaps.
  EXPECT_EQ(undone.value().mesh.points, off.value().mesh.points);
  EXPECT_EQ(undone.value().mesh.triangles, off.value().mesh.triangles);
  EXPECT_EQ(undone_stats.input_gap_vertices, off_stats.input_gap_vertices);
  EXPECT_EQ(undone.value().input_gaps, off.value().input_gaps);
  // Counted before the first round, and that surface is the one kept.
  EXPECT_EQ(undone_stats.self_intersections,
            int64_t(find_self_intersections(undone.value().mesh, 0).pairs));
}

TEST(RemeshSurface, SizeRoundsRefineAroundWhatTheWallCannotFollow) {
  // The aneurysm phantom: its neck bends tighter than a wall of 0.3 can
  // follow, so pinning alone leaves input vertices far from it.
  const SurfaceMesh in = testing::phantom(PhantomKind::kAneurysm, true, 0.1, 0.1);
  const double h = 0.3;
  RemeshOptions o = testing::uniform_remesh(h);
  RemeshStats off_stats, on_stats;
  o.fidelity_size_rounds = 0;
  auto off = remesh_surface(in, o, &off_stats);
  o.fidelity_size_rounds = RemeshOptions().fidelity_size_rounds;
  auto on = remesh_surface(in, o, &on_stats);
  ASSERT_TRUE(off.ok()) << off.message();
  ASSERT_TRUE(on.ok()) << on.message();
  std::vector<double> lengths;
  const SurfaceMesh& m = on.value().mesh;
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const double* a = &m.points[3 * size_t(m.triangles[3 * t + size_t(k)])];
      const double* b = &m.points[3 * size_t(m.triangles[3 * t + size_t(k + 1) % 3])];
      lengths.push_back(std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
    }
  const double median = testing::median(lengths);
  const QualityStats q = quality_stats(triangle_qualities(m));
  std::cout << "[ info ] far input vertices " << off_stats.input_gap_vertices << " -> "
            << on_stats.input_gap_vertices << " (" << on_stats.fidelity_size_rounds
            << " size rounds, sizes " << on_stats.size_min << ".." << on_stats.size_max
            << "), median edge " << median / h << " h, gamma min " << q.min << " mean " << q.mean
            << "\n";
  EXPECT_GE(on_stats.fidelity_size_rounds, 1u);
  EXPECT_GT(off_stats.input_gap_vertices, 10u);
  EXPECT_EQ(on_stats.input_gap_vertices, 0u);
  // Finer only where needed: the sizes stay within [h/4, h] and the median
  // edge within the drift allowed of h.
  EXPECT_LT(on_stats.size_min, h);
  EXPECT_GE(on_stats.size_min, h / 4);
  EXPECT_EQ(on_stats.size_max, h);
  EXPECT_GT(median, (1 - o.fidelity_size_drift - 0.02) * h);
  EXPECT_LT(median, 1.1 * h);
  EXPECT_GE(q.min, 0.55);
  EXPECT_GE(q.mean, 0.97);
  EXPECT_EQ(analyze_topology(m).openings.size(), 3u);
  EXPECT_LE(distances_to_surface(in, m.points).max, 1e-9);
  // The reported gaps are those of the final surface, and the far ones
  // are counted against the asked h, not the finer sizes of the rounds.
  const std::vector<double> gaps = distances_to_surface(m, in.points, true).per_point;
  for (size_t v = 0; v < gaps.size(); ++v) EXPECT_NEAR(gaps[v], on.value().input_gaps[v], 1e-12);
  EXPECT_EQ(on_stats.input_gap_vertices,
            size_t(std::count_if(gaps.begin(), gaps.end(), [&](double g) { return g > 0.1 * h; })));
  // So is the reported median edge.
  EXPECT_NEAR(on_stats.edge_ratio_median, median / h, 0.01);
}

TEST(RemeshSurface, TheWallsOwnChordErrorSizesItBeforeThePins) {
  // The bifurcation phantom at 0.3: the first wall (phases 2-4) leaves input
  // vertices far; the sizes finer around them leave fewer for the pins.
  const SurfaceMesh in = testing::phantom(PhantomKind::kBifurcation, true, 0.1, 0.1);
  const double h = 0.3;
  RemeshOptions o = testing::uniform_remesh(h);
  RemeshStats pins_only, sized;
  o.fidelity_size_rounds = 0;
  o.fidelity_local_rounds = 0;
  auto off = remesh_surface(in, o, &pins_only);
  o = testing::uniform_remesh(h);
  auto on = remesh_surface(in, o, &sized);
  ASSERT_TRUE(off.ok()) << off.message();
  ASSERT_TRUE(on.ok()) << on.message();
  std::cout << "[ info ] pinned " << pins_only.fidelity_pinned << " -> " << sized.fidelity_pinned
            << " in " << pins_only.fidelity_rounds << " -> " << sized.fidelity_rounds
            << " rounds; far left " << pins_only.input_gap_vertices << " -> "
            << sized.input_gap_vertices << "; size rounds " << sized.fidelity_size_rounds
            << ", sizes " << sized.size_min << ".." << sized.size_max << "\n";
  EXPECT_GE(sized.fidelity_size_rounds, 1u);
  EXPECT_LT(sized.size_min, h);
  EXPECT_GE(sized.size_min, h / 2);
  EXPECT_EQ(sized.size_max, h);
  EXPECT_LT(sized.fidelity_pinned, pins_only.fidelity_pinned);
  EXPECT_EQ(sized.input_gap_vertices, 0u);
  EXPECT_LE(sized.max_input_gap, o.fidelity);
  const QualityStats q = quality_stats(triangle_qualities(on.value().mesh));
  EXPECT_GE(q.min, o.fidelity_floor_min);
  EXPECT_GE(q.mean, o.fidelity_floor_mean);
  EXPECT_EQ(find_self_intersections(on.value().mesh, 0).pairs, 0u);
  // Where the probe's meshing went: counted as fidelity's, not twice.
  EXPECT_GT(sized.seconds_fidelity, 0);
}

TEST(RemeshSurface, LargeWallsPinDownToTheQualityFloor) {
  // Without size rounds (a wall taken as large, few far vertices), the
  // last pinning rounds accept triangles down to the seed's floor.
  const SurfaceMesh in = testing::phantom(PhantomKind::kAneurysm, true, 0.1, 0.1);
  RemeshOptions o = testing::uniform_remesh(0.3);
  o.fidelity_size_rounds = 0;
  o.fidelity_local_rounds = 0;
  // The relaxation free to spread, as the floor is what this compares.
  o.fidelity_relax_rings = -1;
  RemeshStats small_stats, large_stats;
  auto small = remesh_surface(in, o, &small_stats);
  o.fidelity_small_surface = 0;
  auto large = remesh_surface(in, o, &large_stats);
  ASSERT_TRUE(small.ok()) << small.message();
  ASSERT_TRUE(large.ok()) << large.message();
  const QualityStats qs = quality_stats(triangle_qualities(small.value().mesh));
  const QualityStats ql = quality_stats(triangle_qualities(large.value().mesh));
  std::cout << "[ info ] far input vertices " << small_stats.input_gap_vertices << " -> "
            << large_stats.input_gap_vertices << ", gamma_k min " << qs.min << " -> " << ql.min
            << "\n";
  EXPECT_LT(large_stats.input_gap_vertices, small_stats.input_gap_vertices);
  EXPECT_GE(ql.min, o.fidelity_floor_min);
  EXPECT_GE(ql.mean, o.fidelity_floor_mean);
}

}  // namespace
}  // namespace vm
