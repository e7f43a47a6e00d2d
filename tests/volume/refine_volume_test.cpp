#include "core/volume/refine_volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh/volume_mesh.h"
#include "core/util/parallel.h"
#include "tests/support/volume_inputs.h"

namespace vm {
namespace {

struct Prepared {
  testing::VolumeInput in;
  VolumeSizeField field;
  std::vector<double> vertex_h;
};

/// The convex region of the surface `points` (testing::convex_input), its
/// size field (the points' sizes graded by `gradation`, capped by
/// core_size when > 0) and h at each vertex.
void prepare(Prepared& p, std::vector<double> points, double gradation, double core_size = 0) {
  ASSERT_TRUE(testing::convex_input(std::move(points), &p.in));
  std::vector<double> pts, sizes;
  for (size_t v = 0; v < p.in.kernel.num_vertices(); ++v) {
    pts.insert(pts.end(), p.in.kernel.point(int32_t(v)), p.in.kernel.point(int32_t(v)) + 3);
    sizes.push_back(p.in.sizes[v]);
  }
  VolumeSizeOptions o;
  o.gradation = gradation;
  o.core_size = core_size;
  auto f = VolumeSizeField::build(pts, sizes, o);
  ASSERT_TRUE(f.ok()) << f.message();
  p.field = f.value();
  for (size_t v = 0; v < p.in.kernel.num_vertices(); ++v)
    p.vertex_h.push_back(p.field(p.in.kernel.point(int32_t(v))));
}

/// A refinement's result: the kernel's points and finite tetrahedra, and
/// its stats.
struct Outcome {
  std::vector<double> points;
  std::vector<int32_t> tets;
  RefineStats st;
};

double region_volume(const Delaunay3D& d) {
  double v = 0;
  d.for_each_finite_tet([&](int32_t t) {
    if (d.tag(t) != 1) return;
    const int32_t* q = d.tet(t);
    v += tet_volume6(d.point(q[0]), d.point(q[1]), d.point(q[2]), d.point(q[3])) / 6;
  });
  return v;
}

TEST(RefineVolume, CubeInteriorPointsOnlyAndSurfaceKept) {
  Prepared p;
  ASSERT_NO_FATAL_FAILURE(prepare(p, testing::cube_surface_points(8), 0.25));
  const size_t n0 = p.in.kernel.num_vertices();
  RefineStats st;
  ASSERT_TRUE(refine_volume(p.in.kernel, p.field, p.vertex_h, RefineOptions{}, &st).ok());
  const Delaunay3D& d = p.in.kernel;
  ASSERT_TRUE(d.check(false).ok()) << d.check(false).message();
  EXPECT_GT(st.inserted, 50);
  EXPECT_GT(st.first_layer, 0);
  EXPECT_EQ(size_t(st.inserted), d.num_vertices() - n0);
  EXPECT_EQ(p.vertex_h.size(), d.num_vertices());
  // Every surface triangle is still a constrained face, no other face is.
  size_t constrained = 0;
  d.for_each_finite_tet([&](int32_t t) {
    for (int k = 0; k < 4; ++k) constrained += d.is_constrained(t, k);
  });
  EXPECT_EQ(constrained, p.in.surface.num_triangles());
  for (size_t i = 0; i < p.in.surface.triangles.size(); i += 3) {
    int k = -1;
    const int32_t t = d.find_face(p.in.surface.triangles[i], p.in.surface.triangles[i + 1],
                                  p.in.surface.triangles[i + 2], &k);
    ASSERT_GE(t, 0);
    EXPECT_TRUE(d.is_constrained(t, k));
  }
  // New points strictly inside, away from the faces; sizes exact.
  for (size_t v = n0; v < d.num_vertices(); ++v) {
    const double* x = d.point(int32_t(v));
    const double h = p.field(x);
    EXPECT_EQ(p.vertex_h[v], h);
    for (int c = 0; c < 3; ++c) {
      EXPECT_GT(x[c], 0.3 * h);
      EXPECT_LT(x[c], 1 - 0.3 * h);
    }
  }
  // Boundary vertices did not move.
  EXPECT_NEAR(region_volume(d), 1.0, 1e-12);
}

TEST(RefineVolume, SpacingRespectedNearSurfaceAndFront) {
  Prepared p;
  ASSERT_NO_FATAL_FAILURE(prepare(p, testing::sphere_points(3), 0.2));
  const size_t n0 = p.in.kernel.num_vertices();
  RefineOptions o;
  RefineStats st;
  ASSERT_TRUE(refine_volume(p.in.kernel, p.field, p.vertex_h, o, &st).ok());
  const Delaunay3D& d = p.in.kernel;
  // Nearest-neighbor distances of the new points, in units of h: the
  // filter checks the neighborhood only, so allow a few exceptions.
  size_t too_close = 0;
  for (size_t v = n0; v < d.num_vertices(); ++v) {
    double best = 1e300;
    for (size_t w = 0; w < d.num_vertices(); ++w) {
      if (w == v) continue;
      const double* a = d.point(int32_t(v));
      const double* b = d.point(int32_t(w));
      best =
          std::min(best, std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                                   (a[2] - b[2]) * (a[2] - b[2])));
    }
    too_close += best < 0.5 * p.vertex_h[v];
  }
  EXPECT_LE(too_close, (d.num_vertices() - n0) / 100);
  EXPECT_GT(st.generations, 1);
}

TEST(RefineVolume, DeterministicAndCancellable) {
  auto run = [](std::vector<double>* pts) {
    Prepared p;
    ASSERT_NO_FATAL_FAILURE(prepare(p, testing::capped_cylinder_points(1, 3, 0.3), 0.25));
    ASSERT_TRUE(refine_volume(p.in.kernel, p.field, p.vertex_h, RefineOptions{}, nullptr).ok());
    *pts = p.in.kernel.points();
  };
  std::vector<double> a, b;
  run(&a);
  run(&b);
  EXPECT_EQ(a, b);

  Prepared p;
  ASSERT_NO_FATAL_FAILURE(prepare(p, testing::capped_cylinder_points(1, 3, 0.3), 0.25));
  Status s = refine_volume(p.in.kernel, p.field, p.vertex_h, RefineOptions{}, nullptr,
                           [](double, std::string_view) { return false; });
  EXPECT_FALSE(s.ok());
  EXPECT_TRUE(s.cancelled());
}

// Four slabs, down to 16 items each (the small test inputs reach them).
RefineOptions four_slabs() {
  RefineOptions o;
  o.parts = 4;
  o.min_slab_items = 16;
  return o;
}

TEST(RefineVolume, SlabRoundsGiveTheSameMeshOnAnyThreadCount) {
  // Four slabs insert the first layer at the same time, then refine the
  // front, then what they deferred goes on in later rounds and a last
  // sequential one: a valid refinement, as dense as the sequential one, and
  // the same on 1 and 2 threads.
  auto run = [](int threads, int rounds) {
    set_thread_count(threads);
    Outcome out;
    Prepared p;
    EXPECT_NO_FATAL_FAILURE(prepare(p, testing::capped_cylinder_points(1, 4, 0.12), 0.25));
    const size_t n0 = p.in.kernel.num_vertices();
    RefineOptions o = four_slabs();
    o.rounds = rounds;
    EXPECT_TRUE(refine_volume(p.in.kernel, p.field, p.vertex_h, o, &out.st).ok());
    const Delaunay3D& d = p.in.kernel;
    EXPECT_TRUE(d.check(false).ok()) << d.check(false).message();
    EXPECT_EQ(size_t(out.st.inserted), d.num_vertices() - n0);
    EXPECT_EQ(p.vertex_h.size(), d.num_vertices());
    for (size_t v = n0; v < d.num_vertices(); ++v)
      EXPECT_EQ(p.vertex_h[v], p.field(d.point(int32_t(v))));
    out.points = d.points();
    out.tets = d.finite_tets();
    set_thread_count(0);
    return out;
  };
  const Outcome seq = run(2, 0), one = run(1, 3), two = run(2, 3);
  EXPECT_EQ(seq.st.rounds, 0);
  EXPECT_GE(one.st.first_layer_rounds, 1);
  EXPECT_GT(one.st.rounds, one.st.first_layer_rounds);  // and the front's
  EXPECT_GT(one.st.deferred, 0);
  EXPECT_NEAR(double(one.st.first_layer), double(seq.st.first_layer),
              0.05 * double(seq.st.first_layer));
  EXPECT_NEAR(double(one.st.inserted), double(seq.st.inserted), 0.05 * double(seq.st.inserted));
  EXPECT_EQ(one.points, two.points);
  EXPECT_EQ(one.tets, two.tets);
  EXPECT_EQ(one.st.deferred, two.st.deferred);

  // Cancelled during a slab round (the first layer's, the front's): the
  // kernel stays valid, and cancelled in the first layer's, it holds fewer
  // vertices than the first layer inserts.
  for (bool first_layer : {true, false}) {
    Prepared p;
    ASSERT_NO_FATAL_FAILURE(prepare(p, testing::capped_cylinder_points(1, 4, 0.12), 0.25));
    const size_t n0 = p.in.kernel.num_vertices();
    RefineOptions o = four_slabs();
    o.first_layer = first_layer;
    int calls = 0;
    Status s = refine_volume(p.in.kernel, p.field, p.vertex_h, o, nullptr,
                             [&](double, std::string_view) { return ++calls < 2; });
    EXPECT_TRUE(s.cancelled());
    EXPECT_TRUE(p.in.kernel.check(false).ok()) << p.in.kernel.check(false).message();
    if (first_layer) {
      EXPECT_LT(p.in.kernel.num_vertices() - n0, size_t(one.st.first_layer));
    }
  }
}

TEST(RefineVolume, FineCoreStaysInTheSlabRounds) {
  // A core almost four times finer than the wall: each front vertex fills far
  // more than the 3 vertices a slab may insert per item in its first round,
  // so the slabs run out of budget. The rounds that follow, with doubled
  // budgets, leave at most half as much to the sequential round as when
  // the budget rounds are off, for the same refinement; the same on 1 and
  // 2 threads.
  auto run = [](int threads, int budget_rounds) {
    set_thread_count(threads);
    Outcome out;
    Prepared p;
    // Along x, so that the first round cuts across the vessel.
    std::vector<double> wall = testing::capped_cylinder_points(0.25, 4, 0.15);
    for (size_t i = 0; i < wall.size(); i += 3) std::rotate(&wall[i], &wall[i + 2], &wall[i + 3]);
    EXPECT_NO_FATAL_FAILURE(prepare(p, std::move(wall), VolumeSizeOptions{}.gradation, 0.04));
    RefineOptions o;
    o.min_slab_items = 64;
    o.budget_rounds = budget_rounds;
    EXPECT_TRUE(refine_volume(p.in.kernel, p.field, p.vertex_h, o, &out.st).ok());
    EXPECT_TRUE(p.in.kernel.check(false).ok()) << p.in.kernel.check(false).message();
    out.points = p.in.kernel.points();
    out.tets = p.in.kernel.finite_tets();
    set_thread_count(0);
    return out;
  };
  const Outcome off = run(2, 0), one = run(1, RefineOptions{}.budget_rounds),
                two = run(2, RefineOptions{}.budget_rounds);
  EXPECT_GT(off.st.inserted, 10000);
  EXPECT_EQ(off.st.rounds - off.st.first_layer_rounds, RefineOptions{}.rounds);
  EXPECT_GT(one.st.rounds - one.st.first_layer_rounds, RefineOptions{}.rounds);
  EXPECT_NEAR(double(one.st.inserted), double(off.st.inserted), 0.05 * double(off.st.inserted));
  EXPECT_LT(2 * one.st.sequential_inserted, off.st.sequential_inserted);
  EXPECT_EQ(one.points, two.points);
  EXPECT_EQ(one.tets, two.tets);
  EXPECT_EQ(one.st.sequential_inserted, two.st.sequential_inserted);
}

TEST(RefineVolume, Errors) {
  Prepared p;
  ASSERT_NO_FATAL_FAILURE(prepare(p, testing::cube_surface_points(3), 0.25));
  std::vector<double> wrong(3, 0.1);
  EXPECT_FALSE(refine_volume(p.in.kernel, p.field, wrong, RefineOptions{}, nullptr).ok());
  RefineOptions bad;
  bad.min_spacing = 2;
  EXPECT_FALSE(refine_volume(p.in.kernel, p.field, p.vertex_h, bad, nullptr).ok());
  RefineOptions no_budget_rounds;
  no_budget_rounds.budget_rounds = -1;
  const Status sb = refine_volume(p.in.kernel, p.field, p.vertex_h, no_budget_rounds, nullptr);
  EXPECT_FALSE(sb.ok());
  EXPECT_NE(sb.message().find("budget_rounds >= 0"), std::string::npos);
  // A hull face not constrained: the region is open.
  Delaunay3D& d = p.in.kernel;
  bool opened = false;
  d.for_each_finite_tet([&](int32_t t) {
    for (int k = 0; k < 4 && !opened; ++k)
      if (d.is_constrained(t, k)) {
        d.set_constrained(t, k, false);
        opened = true;
      }
  });
  Status s = refine_volume(d, p.field, p.vertex_h, RefineOptions{}, nullptr);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("not closed"), std::string::npos);
}

}  // namespace
}  // namespace vm
